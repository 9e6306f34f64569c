#!/usr/bin/python3
"""Scripted `rqt_reconfigure /gazebo` on a running simulator (gazebo_ros empty_world.launch):
sets the physics step to 0.002 s and gravity z to -3 through the editors, as a student types
them, then prints what /gazebo/get_physics_properties answers."""
import sys

import rospy
from gazebo_msgs.srv import GetPhysicsProperties

from course_testing.rqt_driver import emit, run, running_instance

st = {}


def add_arguments(parser):
    group = parser.add_argument_group('Options for rqt_reconfigure plugin')
    group.add_argument('node_name', nargs='*', default=[])


def physics():
    rospy.wait_for_service('/gazebo/get_physics_properties', 30.0)
    r = rospy.ServiceProxy('/gazebo/get_physics_properties', GetPhysicsProperties)()
    return r.time_step, r.gravity.z


def scenario(main, step):
    p = running_instance(main, 'rqt_reconfigure/Reconfigure')
    ed = p.node_editors.get('/gazebo')
    if ed is None or 'time_step' not in ed.editors:
        return False
    if 'set' not in st:
        st['before'] = physics()
        for name, text in (('time_step', '0.002'), ('gravity_z', '-3')):
            _, w = ed.editors[name]
            w.setText(text)
            w.editingFinished.emit()
        st['set'] = True
        emit(kind='editors', names=sorted(ed.editors), before=list(st['before']))
        return False
    now = physics()
    if now == st['before']:
        return False                      # the server has not applied it yet: next tick
    cfg = p._clients['/gazebo'].get_configuration(timeout=5.0)
    emit(kind='physics', time_step=now[0], gravity_z=now[1], config_time_step=cfg['time_step'],
         config_gravity_z=cfg['gravity_z'], status=p._widget.status.text())
    return now == (0.002, -3.0)


sys.exit(run(['rqt_reconfigure', '/gazebo'], scenario, standalone='rqt_reconfigure.param_plugin.ParamPlugin',
             plugin_argument_provider=add_arguments, timeout=180.0))
