#!/usr/bin/python3
"""Scripted `rqt_robot_steering`: topic /turtle1/cmd_vel, linear slider to 1.0 m/s for 2 s, then
Stop; prints the widget state."""
import sys
import time

from course_testing.rqt_driver import emit, run, running_instance

st = {}


def scenario(main, step):
    p = running_instance(main, 'rqt_robot_steering/RobotSteering')
    w = p._widget
    if 'start' not in st:
        w.topic_line_edit.setText('/turtle1/cmd_vel')
        w.linear_slider.setValue(1000)
        w.angular_slider.setValue(500)
        st['start'] = time.time()
        emit(kind='driving', linear=w.linear_label.text(), angular=w.angular_label.text(),
             topic=w.topic_line_edit.text())
        return False
    if time.time() - st['start'] < 2.0:
        return False
    w.stop_push_button.pressed.emit()
    emit(kind='stopped', linear=w.linear_label.text(), slider=w.linear_slider.value())
    return True


sys.exit(run(['rqt_robot_steering'], scenario, standalone='rqt_robot_steering.robot_steering.RobotSteering'))
