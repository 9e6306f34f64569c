"""Draws a `dot -Tplain` layout into a QGraphicsScene: ellipses/boxes with tooltips, splines."""
import math

from python_qt_binding.QtCore import QPointF, QRectF
from python_qt_binding.QtGui import QBrush, QColor, QPainterPath, QPen, QPolygonF
from python_qt_binding.QtWidgets import (QGraphicsEllipseItem, QGraphicsPathItem,
                                         QGraphicsPolygonItem, QGraphicsRectItem,
                                         QGraphicsSimpleTextItem, QGraphicsView)

DPI = 72.0


class GraphView(QGraphicsView):
    def __init__(self, scene, parent=None):
        super(GraphView, self).__init__(scene, parent)
        self.setRenderHints(self.renderHints())
        self.setDragMode(QGraphicsView.ScrollHandDrag)

    def wheelEvent(self, event):
        factor = 1.15 if event.angleDelta().y() > 0 else 1 / 1.15
        self.scale(factor, factor)


def draw(scene, plain, tooltips=None, colors=None):
    """Fill `scene`; returns ({dot id: shape item}, [(tail, head, path item)])."""
    width, height, nodes, edges = plain
    tooltips = tooltips or {}
    colors = colors or {}
    scene.clear()

    def pt(x, y):
        return QPointF(x * DPI, (height - y) * DPI)

    items = {}
    for nid, n in nodes.items():
        c = pt(n['x'], n['y'])
        w, h = n['w'] * DPI, n['h'] * DPI
        rect = QRectF(c.x() - w / 2, c.y() - h / 2, w, h)
        if n['shape'] == 'ellipse':
            item = QGraphicsEllipseItem(rect)
        else:
            item = QGraphicsRectItem(rect)
        pen = QPen(QColor(colors.get(nid, 'black')))
        pen.setWidthF(1.5)
        item.setPen(pen)
        item.setBrush(QBrush(QColor('white')))
        item.setToolTip(tooltips.get(nid, n['label']))
        scene.addItem(item)
        text = QGraphicsSimpleTextItem(n['label'], item)
        br = text.boundingRect()
        text.setPos(c.x() - br.width() / 2, c.y() - br.height() / 2)
        items[nid] = item
    edge_items = []
    for e in edges:
        p = [pt(x, y) for x, y in e['points']]
        if not p:
            continue
        path = QPainterPath(p[0])
        i = 1
        while i + 2 < len(p):
            path.cubicTo(p[i], p[i + 1], p[i + 2])
            i += 3
        for q in p[i:]:
            path.lineTo(q)
        item = QGraphicsPathItem(path)
        pen = QPen(QColor('black'))
        pen.setWidthF(1.2)
        item.setPen(pen)
        scene.addItem(item)
        head = nodes.get(e['head'])
        if head is not None and len(p) >= 2:
            _arrow(scene, p[-2], p[-1])
        if e['label'] and e['label_pos']:
            t = QGraphicsSimpleTextItem(e['label'])
            lp = pt(*e['label_pos'])
            t.setPos(lp.x() - t.boundingRect().width() / 2, lp.y() - t.boundingRect().height() / 2)
            scene.addItem(t)
        edge_items.append((e['tail'], e['head'], item))
    scene.setSceneRect(QRectF(0, 0, width * DPI, height * DPI))
    return items, edge_items


def _arrow(scene, a, b):
    """An arrowhead continuing the spline end `b` (direction a->b), as graphviz leaves room for."""
    dx, dy = b.x() - a.x(), b.y() - a.y()
    length = math.hypot(dx, dy) or 1.0
    ux, uy = dx / length, dy / length
    size = 8.0
    base = b
    left = QPointF(base.x() - uy * size / 2, base.y() + ux * size / 2)
    right = QPointF(base.x() + uy * size / 2, base.y() - ux * size / 2)
    tri = QGraphicsPolygonItem(QPolygonF([QPointF(b.x() + ux * size, b.y() + uy * size), left, right]))
    tri.setBrush(QBrush(QColor('black')))
    scene.addItem(tri)
