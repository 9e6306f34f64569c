#!/usr/bin/python3
"""Scripted `rqt_publisher` (standalone), practical 5 §6.3 through the GUI: a std_msgs/Float64
publisher on the wheel's position controller command topic (argv[1]) with data = 1.5 at 10 Hz,
enabled through its checkbox until the test creates the stop file (argv[2]), then disabled."""
import os
import sys

from course_testing.rqt_driver import emit, run, running_instance

TOPIC, STOP = sys.argv[1], sys.argv[2]
st = {}


def scenario(main, step):
    p = running_instance(main, 'rqt_publisher/Publisher')
    if 'id' not in st:
        st['id'] = p.add_publisher(TOPIC, 'std_msgs/Float64', 10.0, False)
        p.set_expression(st['id'], '/data', '1.5')
        p.set_enabled(st['id'], True)
        emit(kind='enabled', status=p._widget.status.text())
        return False
    if not os.path.exists(STOP):
        return False
    p.set_enabled(st['id'], False)
    emit(kind='done', counter=p._publishers[st['id']]['counter'])
    return True


sys.exit(run(['rqt_publisher'], scenario, standalone='rqt_publisher.publisher.Publisher', timeout=240.0))
