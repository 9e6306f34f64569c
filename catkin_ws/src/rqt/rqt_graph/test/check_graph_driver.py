#!/usr/bin/python3
"""Scripted `rqt_graph` for test_rqt_graph_gui.py: waits for /talker -> /listener on /chatter,
prints the graph model (nodes only, then nodes/topics) and where the items are on screen, then
waits for the test's screenshot (flag file argv[1])."""
import sys

from course_testing.rqt_driver import emit, file_exists, run, running_instance

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
        # and connected: the edge comes from the listener's getBusInfo, once it connected
        if m is None or not all(any(n.startswith(p) for n in m.nodes) for p in ('/talker', '/listener')) \
                or not any(e[2] == '/chatter' for e in m.edges):
            return False
        emit(mode='node_node', nodes=m.nodes, edges=[list(e) for e in m.edges],
             title=main.main_window.windowTitle())
        w.graph_type_combo_box.setCurrentIndex(1)     # Nodes/Topics (active)
        phase['n'] = 1
        return False
    if phase['n'] == 1:
        m = w.model
        # the talker -> /chatter edge comes from the talker's own getBusInfo (asked at most every
        # 5 s per node): until it answered after the connection, /chatter has one edge and the
        # default "hide leaf topics" hides it, as in the original; refresh as a user would
        if '/chatter' not in m.topics:
            if step % 5 == 0:
                w.refresh()
            return False
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
