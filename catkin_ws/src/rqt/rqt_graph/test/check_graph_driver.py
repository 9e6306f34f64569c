#!/usr/bin/python3
"""Scripted `rqt_graph` for test_rqt_graph_gui.py: waits for /talker -> /listener on /chatter,
prints the graph model (nodes only, then nodes/topics) and where the items are on screen, then
waits for the test's screenshot (flag file argv[1])."""
import sys

from rqt_graph import graph_model
from rqt_graph.graph_model import NODE_TOPIC
from rqt_gui.testing import emit, file_exists, run, running_instance

flag = sys.argv.pop(1)
phase = {'n': 0}


def screen_rect(view, item):
    poly = view.mapFromScene(item.sceneBoundingRect())
    r = poly.boundingRect()
    p = view.viewport().mapToGlobal(r.topLeft())
    return [p.x(), p.y(), r.width(), r.height()]


def scenario(main, step):
    g = running_instance(main, 'rqt_graph/RosGraph')
    if g is None:
        emit(error='rqt_graph/RosGraph is not running')
        return True
    w = g._widget
    if phase['n'] == 0:
        if step % 5 == 0:
            w.refresh()
        m = w.model
        # rospy_tutorials' talker and listener are anonymous: /talker_<pid>_<stamp>
        # and connected: the edges come from each node's getBusInfo, asked at most every 5 s per
        # node — the listener's answer gives the node-to-node edge, the talker's the talker ->
        # /chatter edge of the Nodes/Topics view; wait until both answered after the connection
        if m is None or not all(any(n.startswith(p) for n in m.nodes) for p in ('/talker', '/listener')) \
                or not any(e[2] == '/chatter' for e in m.edges) \
                or '/chatter' not in graph_model.build(w._snapshot, dict(w.options(), graph_type=NODE_TOPIC)).topics:
            return False
        emit(mode='node_node', nodes=m.nodes, edges=[list(e) for e in m.edges],
             title=main.main_window.windowTitle())
        w.graph_type_combo_box.setCurrentIndex(1)     # Nodes/Topics (active)
        phase['n'] = 1
        return False
    if phase['n'] == 1:
        m = w.model
        view = w.graphics_view
        emit(mode=m.graph_type, nodes=m.nodes, topics=m.topics, edges=[list(e[:2]) for e in m.edges],
             rects={k: screen_rect(view, it) for k, it in w.node_items.items()},
             tooltips={k: it.toolTip() for k, it in w.node_items.items()},
             view=[view.viewport().mapToGlobal(view.viewport().rect().topLeft()).x(),
                   view.viewport().mapToGlobal(view.viewport().rect().topLeft()).y(),
                   view.viewport().width(), view.viewport().height()])
        phase['n'] = 2
        return False
    return file_exists(flag)


sys.exit(run(['rqt_graph'] + sys.argv[1:], scenario, standalone='rqt_graph.ros_graph.RosGraph'))
