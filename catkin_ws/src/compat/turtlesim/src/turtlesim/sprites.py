"""Turtle sprites drawn procedurally with QPainter (45x45 px, facing +x before rotation).

Each variant is a shell colour scheme; the sprite is a top view: four legs, a tail, a head
with eyes and a patterned shell. Painting only needs QImage (no display).
"""
import math

from PyQt5.QtCore import QPointF, QRectF, Qt
from PyQt5.QtGui import QBrush, QColor, QImage, QPainter, QPainterPath, QPen

SIZE = 45

# (shell, shell pattern, skin) RGB triples
VARIANTS = (
    ((46, 139, 87), (24, 90, 52), (150, 200, 110)),     # green
    ((160, 110, 50), (105, 70, 30), (210, 180, 120)),   # brown box turtle
    ((40, 110, 170), (20, 65, 110), (140, 200, 210)),   # sea blue
    ((200, 150, 40), (130, 90, 20), (230, 210, 140)),   # yellow
    ((130, 80, 160), (80, 45, 105), (200, 170, 215)),   # violet
    ((190, 70, 60), (120, 40, 35), (235, 170, 150)),    # red
)


def make_sprite(variant=0):
    """A 45x45 ARGB QImage of a turtle facing right (+x)."""
    shell, pattern, skin = (QColor(*c) for c in VARIANTS[variant % len(VARIANTS)])
    img = QImage(SIZE, SIZE, QImage.Format_ARGB32_Premultiplied)
    img.fill(Qt.transparent)
    p = QPainter(img)
    p.setRenderHint(QPainter.Antialiasing)
    p.translate(SIZE / 2.0, SIZE / 2.0)
    outline = QPen(QColor(20, 20, 20), 1.2)
    p.setPen(outline)
    p.setBrush(QBrush(skin))
    # legs: front pair angled forward, back pair angled back
    for sx, sy, ang in ((7, -11, -35), (7, 11, 35), (-9, -11, -145), (-9, 11, 145)):
        p.save()
        p.translate(sx, sy)
        p.rotate(ang)
        p.drawEllipse(QRectF(-2.0, -3.5, 11.0, 7.0))
        p.restore()
    # tail
    tail = QPainterPath()
    tail.moveTo(-15, -2.5)
    tail.lineTo(-21, 0)
    tail.lineTo(-15, 2.5)
    tail.closeSubpath()
    p.drawPath(tail)
    # head and eyes
    p.drawEllipse(QRectF(11.0, -5.0, 10.0, 10.0))
    p.setBrush(QBrush(QColor(10, 10, 10)))
    p.setPen(Qt.NoPen)
    p.drawEllipse(QPointF(17.5, -2.6), 1.2, 1.2)
    p.drawEllipse(QPointF(17.5, 2.6), 1.2, 1.2)
    # shell with a hexagon pattern
    p.setPen(outline)
    p.setBrush(QBrush(shell))
    p.drawEllipse(QRectF(-16.0, -13.0, 30.0, 26.0))
    p.setPen(QPen(pattern, 1.6))
    p.setBrush(Qt.NoBrush)
    hexagon = QPainterPath()
    for k in range(6):
        a = math.pi / 3.0 * k
        pt = QPointF(-1.0 + 6.0 * math.cos(a), 6.0 * math.sin(a))
        if k == 0:
            hexagon.moveTo(pt)
        else:
            hexagon.lineTo(pt)
    hexagon.closeSubpath()
    p.drawPath(hexagon)
    for k in range(6):
        a = math.pi / 3.0 * k
        p.drawLine(QPointF(-1.0 + 6.0 * math.cos(a), 6.0 * math.sin(a)),
                   QPointF(-1.0 + 12.5 * math.cos(a), 10.8 * math.sin(a)))
    p.end()
    return img


def count():
    return len(VARIANTS)
