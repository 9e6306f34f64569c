#!/usr/bin/python3
"""Scripted `rqt_gui -p monitor` with Topic Monitor and Console (loaded through the Plugins menu)
while rospy_tutorials' talker runs: /chatter monitored (type, Hz, bandwidth, value), a topic of an
unknown type, the talker's log lines in the Console and the severity exclude filter."""
import sys
import time

from course_testing.rqt_driver import emit, run, running_instance

st = {'phase': 0}


def trigger(main, plugin_id):
    from python_qt_binding.QtWidgets import QAction
    for a in main.main_window.findChildren(QAction):
        if a.objectName() == 'plugin_action__' + plugin_id:
            a.trigger()
            return
    raise AssertionError('no Plugins menu entry for ' + plugin_id)


def scenario(main, step):
    if st['phase'] == 0:
        trigger(main, 'rqt_topic/TopicPlugin')
        trigger(main, 'rqt_console/Console')
        st['phase'] = 1
        return False
    t = running_instance(main, 'rqt_topic/TopicPlugin')._widget
    c = running_instance(main, 'rqt_console/Console')._widget
    if st['phase'] == 1:
        if '/chatter' not in t.items:
            return False
        t.set_monitored('/chatter', True)
        from rqt_topic.topic import SortItem
        fake = SortItem(['/fake', 'no_pkg/NoType', '', '', 'not monitored'])
        from python_qt_binding.QtCore import Qt
        fake.setFlags(fake.flags() | Qt.ItemIsUserCheckable)
        fake.setCheckState(0, Qt.Unchecked)
        t.topics_tree_widget.addTopLevelItem(fake)
        t.items['/fake'] = fake
        t.set_monitored('/fake', True)
        st['fake'] = fake.text(4)          # (the row goes at the next refresh: not published)
        st['phase'] = 2
        st['t0'] = time.time()
        return False
    if st['phase'] == 2:
        item = t.items['/chatter']
        talker_rows = [m for m in c.model.rows if m.node.startswith('/talker')]
        if time.time() - st['t0'] < 4.0 or item.childCount() == 0 or len(talker_rows) < 3:
            return False
        emit(kind='monitor', row=[item.text(k) for k in range(5)],
             children=[[item.child(k).text(0), item.child(k).text(4)] for k in range(item.childCount())],
             fake=st['fake'],
             console=[[m.message, m.severity, m.node] for m in talker_rows[:3]],
             status=c.status_label.text())
        c.severity_boxes[2].setChecked(True)          # exclude Info
        emit(kind='excluded', talker_rows=len([m for m in c.model.rows if m.node.startswith('/talker')]),
             status=c.status_label.text())
        return True


sys.exit(run(['rqt_gui', '-p', 'monitor'], scenario))
