#!/usr/bin/env python3
"""A client of sim_node used by test_spawn_pose.py: spawns through /gazebo/spawn_sdf_model and
spawn_urdf_model as gazebo_ros' users do (models with their own <pose>, includes with and
without <pose>), then prints one JSON object: each model's state pose
[x, y, z, qx, qy, qz, qw] and the get_world_sdf text.

  spawn_pose_client.py spawn     the spawns (prints their [success, status_message] too)
  spawn_pose_client.py state     the poses and the world SDF only
"""
import json
import sys

import rospy
from gazebo_msgs import srv as gs
from geometry_msgs.msg import Point, Pose, Quaternion
from ode_sim_msgs.srv import GetWorldSDF

BOX = ('<link name="link"><inertial><mass>1</mass><inertia><ixx>0.1</ixx><iyy>0.1</iyy>'
       '<izz>0.1</izz></inertia></inertial><collision name="c"><geometry><box><size>0.2 0.2 0.2'
       '</size></box></geometry></collision></link>')
POSED = '<sdf version="1.6"><model name="from_file"><pose>1 0 0.5 0 0 0.3</pose>%s</model></sdf>' \
    % BOX
INCLUDE_POSED = ('<sdf version="1.6"><include><uri>model://posed_box</uri><pose>0 1 0 0 0 0</pose>'
                 '</include></sdf>')
INCLUDE_BARE = ('<sdf version="1.4"><world name="default"><include><uri>model://posed_box</uri>'
                '</include></world></sdf>')
ROBOT = ('<robot name="r"><origin xyz="0 0 1" rpy="0 0 0"/><link name="base"><inertial>'
         '<mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/>'
         '</inertial><collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>'
         '</link></robot>')


def svc(name, typ):
    rospy.wait_for_service(name, timeout=120)   # a hang guard: a loaded machine starts slowly
    return rospy.ServiceProxy(name, typ)


def yaw_pose(x, y, z, yaw):
    import math
    return Pose(Point(x, y, z), Quaternion(0, 0, math.sin(yaw / 2), math.cos(yaw / 2)))


def state(out):
    world = svc('/gazebo/get_world_properties', gs.GetWorldProperties)()
    get_state = svc('/gazebo/get_model_state', gs.GetModelState)
    out['models'] = {}
    for name in world.model_names:
        p = get_state(name, '').pose
        out['models'][name] = [p.position.x, p.position.y, p.position.z, p.orientation.x,
                               p.orientation.y, p.orientation.z, p.orientation.w]
    out['sdf'] = svc('/gazebo/get_world_sdf', GetWorldSDF)().sdf
    return out


def spawn(out):
    import math
    sdf = svc('/gazebo/spawn_sdf_model', gs.SpawnModel)
    urdf = svc('/gazebo/spawn_urdf_model', gs.SpawnModel)
    for key, call, name, xml, pose in (
            ('posed', sdf, 'posed', POSED, yaw_pose(2, 3, 0, math.pi / 2)),
            ('include_posed', sdf, 'inc_posed', INCLUDE_POSED, yaw_pose(3, 0, 0, math.pi / 2)),
            ('include_bare', sdf, 'inc_bare', INCLUDE_BARE, yaw_pose(-1, -2, 0, 0.2)),
            ('robot', urdf, 'bot', ROBOT, yaw_pose(1, 0, 0, 0))):
        r = call(name, xml, '', pose, 'world')
        out[key] = [r.success, r.status_message]
    return out


def main(argv):
    rospy.init_node('spawn_pose_client', anonymous=True)
    out = {}
    if argv[1] == 'spawn':
        spawn(out)
    print(json.dumps(state(out)))


if __name__ == '__main__':
    main(rospy.myargv(sys.argv))
