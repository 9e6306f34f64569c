"""The TurtleSim window: a fixed 500x500 QWidget painting the path layer and the sprites.

The simulation runs on a worker thread (sim_node.TurtleSimNode.run); after each tick it emits
`changed`, a Qt signal, which queues a repaint on the GUI thread. paintEvent reads the world
under the simulation's lock.
"""
import math

from PyQt5.QtCore import pyqtSignal
from PyQt5.QtGui import QPainter
from PyQt5.QtWidgets import QWidget

from turtlesim import sprites
from turtlesim.canvas import to_pixels
from turtlesim.world import WINDOW_PX


class TurtleWindow(QWidget):
    changed = pyqtSignal()

    def __init__(self, sim):
        super().__init__()
        self.sim = sim
        self.sprite_images = [sprites.make_sprite(i) for i in range(sprites.count())]
        self.setFixedSize(WINDOW_PX, WINDOW_PX)
        self.setWindowTitle('TurtleSim')
        self.changed.connect(self.update)

    def notify(self):
        """Thread-safe: called by the simulation thread after a tick."""
        self.changed.emit()

    def paintEvent(self, _event):
        painter = QPainter(self)
        with self.sim.lock:
            painter.drawImage(0, 0, self.sim.canvas.image)
            turtles = self.sim.snapshot()
        painter.setRenderHint(QPainter.SmoothPixmapTransform)
        for sprite, x, y, theta in turtles:
            img = self.sprite_images[sprite % len(self.sprite_images)]
            px, py = to_pixels(x, y)
            painter.save()
            painter.translate(px, py)
            painter.rotate(-math.degrees(theta))
            painter.drawImage(int(-img.width() / 2), int(-img.height() / 2), img)
            painter.restore()
        painter.end()
