#!/usr/bin/python3
"""Scripted `rqt_publisher` (standalone): a Twist publisher on /turtle1/cmd_vel at 10 Hz with
linear/x = 1.0 and angular/z = 0.5, enabled through its checkbox for 20 messages (2 s at
10 Hz: a count, not the wall clock, so a loaded machine sends as many), then disabled."""
import sys

from course_testing.rqt_driver import emit, run, running_instance

st = {}


def scenario(main, step):
    p = running_instance(main, 'rqt_publisher/Publisher')
    if 'id' not in st:
        st['id'] = p.add_publisher('/turtle1/cmd_vel', 'geometry_msgs/Twist', 10.0, False)
        p.set_expression(st['id'], '/linear/x', '1.0')
        p.set_expression(st['id'], '/angular/z', '0.5')
        p.set_expression(st['id'], '/linear/y', 'not a number')
        p.set_enabled(st['id'], True)
        top = p._widget.publisher_tree_widget.topLevelItem(0)
        emit(kind='enabled', bad_cell=top.child(0).child(1).text(3), status=p._widget.status.text())
        return False
    if p._publishers[st['id']]['counter'] < 20:
        return False
    p.set_enabled(st['id'], False)
    emit(kind='done', counter=p._publishers[st['id']]['counter'])
    return True


sys.exit(run(['rqt_publisher'], scenario, standalone='rqt_publisher.publisher.Publisher'))
