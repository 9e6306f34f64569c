"""The drawing layer: a 500x500 QImage (background + trails) painted with QPainter.

Works headless: QImage and QPainter need neither a display nor a QApplication. Coordinates
given to it are world metres (y up); it converts to pixels (y down) with 45 px per metre.
"""
from PyQt5.QtCore import QPointF
from PyQt5.QtGui import QColor, QImage, QPainter, QPen

from turtlesim.world import METER_PX, WINDOW_PX, WORLD_SIZE


def to_pixels(x, y):
    """World metres -> window pixel coordinates (floats, y down)."""
    return x * METER_PX, (WORLD_SIZE - y) * METER_PX


def _round(v):
    # qRound for the non-negative values used here
    return int(v + 0.5) if v >= 0 else -int(-v + 0.5)


class Canvas:
    """The persistent path image shared by the simulation (writes) and the window (reads)."""

    def __init__(self, size=WINDOW_PX):
        self.image = QImage(size, size, QImage.Format_RGB32)
        self.image.fill(QColor(0, 0, 0))

    def fill(self, rgb):
        self.image.fill(QColor(*rgb))

    def draw_line(self, p0, p1, pen):
        qpen = QPen(QColor(*pen.rgb))
        qpen.setWidth(int(pen.width))
        painter = QPainter(self.image)
        try:
            painter.setPen(qpen)
            painter.drawLine(QPointF(*to_pixels(*p0)), QPointF(*to_pixels(*p1)))
        finally:
            painter.end()

    def pixel(self, p):
        """(r, g, b) of the pixel under world point p (clamped to the image)."""
        px, py = to_pixels(*p)
        w, h = self.image.width(), self.image.height()
        ix = min(max(_round(px), 0), w - 1)
        iy = min(max(_round(py), 0), h - 1)
        c = QColor(self.image.pixel(ix, iy))
        return c.red(), c.green(), c.blue()

    def copy(self):
        return self.image.copy()
