#!/usr/bin/env python3
"""A client of sim_node's window API used by test_world_control.py, as a window drives it:

  world_control_client.py edit SAVED_FILE   insert an include, a box, a URDF robot and a light,
      move one, delete one, step while running (refused), pause, step 100, read the statistics,
      save the world to SAVED_FILE; prints one JSON object of observations
  world_control_client.py state             the models' poses, the robots' link poses and joint
      positions, the lights, the joints of the arm's ros_control bridge (after a restart on the
      saved file); prints one JSON object
  world_control_client.py arm_urdf          prints the arm's URDF (the robot_description)
"""
import json
import sys
import time

import rospy
from gazebo_msgs import srv as gs
from gazebo_msgs.msg import ModelState
from geometry_msgs.msg import Point, Pose, Quaternion
from ode_sim_msgs.msg import WorldStatistics
from ode_sim_msgs.srv import GetWorldSDF, StepWorld
from std_srvs.srv import Empty

ARM = """<?xml version="1.0"?>
<robot name="arm">
  <link name="base"><inertial><mass value="5"/>
      <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
    <collision><geometry><box size="0.4 0.4 0.2"/></geometry></collision>
    <visual><geometry><box size="0.4 0.4 0.2"/></geometry></visual></link>
  <link name="arm"><inertial><origin xyz="0.25 0 0"/><mass value="0.5"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <collision><origin xyz="0.25 0 0"/><geometry><box size="0.5 0.05 0.05"/></geometry></collision></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.3"/><axis xyz="0 0 1"/><limit lower="-2" upper="2" effort="10" velocity="1"/>
    <dynamics damping="5"/></joint>
  <gazebo reference="base"><material>Gazebo/Blue</material></gazebo>
  <transmission name="shoulder_trans"><type>transmission_interface/SimpleTransmission</type>
    <joint name="shoulder"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="shoulder_motor"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>
  <gazebo><plugin name="gazebo_ros_control" filename="libgazebo_ros_control.so">
    <controllerNode>false</controllerNode></plugin></gazebo>
</robot>"""

BOX = """<?xml version="1.0"?>
<sdf version="1.6"><model name="box"><link name="link">
  <inertial><mass>1</mass><inertia><ixx>0.015</ixx><iyy>0.015</iyy><izz>0.015</izz></inertia></inertial>
  <collision name="collision"><geometry><box><size>0.3 0.3 0.3</size></box></geometry></collision>
  <visual name="visual"><geometry><box><size>0.3 0.3 0.3</size></box></geometry>
    <material><ambient>1 0 0 1</ambient><diffuse>1 0 0 1</diffuse></material></visual>
</link></model></sdf>"""

INCLUDE = '<sdf version="1.6"><include><uri>model://traffic_cone</uri></include></sdf>'
LIGHT = """<sdf version="1.6"><light name="l" type="point"><pose>0 0 3 0 0 0</pose>
  <diffuse>0.9 0.9 0.8 1</diffuse><attenuation><range>15</range></attenuation></light></sdf>"""

ROBOT_LINKS = {'arm': ['base', 'arm']}


def svc(name, typ):
    rospy.wait_for_service(name, timeout=120)   # a hang guard: a loaded machine starts slowly
    return rospy.ServiceProxy(name, typ)


def pose(x, y, z, qz=0.0, qw=1.0):
    return Pose(Point(x, y, z), Quaternion(0, 0, qz, qw))


def pose_list(p):
    return [p.position.x, p.position.y, p.position.z,
            p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w]


def stats(timeout=60.0):
    return rospy.wait_for_message('/gazebo/world_stats', WorldStatistics, timeout=timeout)


def state():
    out = {'models': {}, 'links': {}, 'joints': {}}
    world = svc('/gazebo/get_world_properties', gs.GetWorldProperties)()
    out['sim_time'] = world.sim_time
    get_state = svc('/gazebo/get_model_state', gs.GetModelState)
    get_link = svc('/gazebo/get_link_state', gs.GetLinkState)
    for name in world.model_names:
        out['models'][name] = pose_list(get_state(name, '').pose)
        for link in ROBOT_LINKS.get(name, []):
            out['links']['%s::%s' % (name, link)] = pose_list(
                get_link('%s::%s' % (name, link), '').link_state.pose)
    if 'arm' in world.model_names:
        r = svc('/gazebo/get_joint_properties', gs.GetJointProperties)('shoulder')
        out['joints']['shoulder'] = r.position[0]
    lp = svc('/gazebo/get_light_properties', gs.GetLightProperties)
    out['lights'] = {n: lp(n).success for n in ('sun', 'lamp_1')}
    # the windows' pose topic (paused world: published all the same)
    from ode_sim_msgs.msg import PoseInfo
    info = rospy.wait_for_message('/gazebo/pose_info', PoseInfo, timeout=60)
    out['pose_info'] = {'models': dict(zip(info.model_name, map(pose_list, info.model_pose))),
                        'links': dict(zip(info.link_name, map(pose_list, info.link_pose))),
                        'iterations': info.iterations}
    return out


def control_joints():
    """The joints the arm's ros_control bridge serves (its state topic, over a few steps of
    the paused world)."""
    from sensor_msgs.msg import JointState
    got = []
    sub = rospy.Subscriber('/arm/ode_sim/joint_states', JointState, lambda m: got.append(m))
    step = svc('/gazebo/step_world', StepWorld)
    deadline = time.monotonic() + 60
    while not got and time.monotonic() < deadline:
        step(5)
        time.sleep(0.1)
    sub.unregister()
    return list(got[-1].name) if got else []


def edit(saved_file):
    out = {}
    spawn_sdf = svc('/gazebo/spawn_sdf_model', gs.SpawnModel)
    spawn_urdf = svc('/gazebo/spawn_urdf_model', gs.SpawnModel)
    step = svc('/gazebo/step_world', StepWorld)
    r = spawn_sdf('cone_a', INCLUDE, '', pose(1, 1, 0, 0.3826834, 0.9238795), 'world')
    out['spawn_include'] = [r.success, r.status_message]
    r = spawn_sdf('box_a', BOX, '', pose(2, 0, 0.15), 'world')
    out['spawn_box'] = [r.success, r.status_message]
    r = spawn_urdf('arm', ARM, '/arm', pose(0, -2, 0.1), 'world')
    out['spawn_urdf'] = [r.success, r.status_message]
    r = spawn_sdf('lamp_1', LIGHT, '', pose(1, 0, 0), 'world')
    out['spawn_light'] = [r.success, r.status_message]
    from ode_sim.description.walls import walls_model
    r = spawn_sdf('walls_1', walls_model('walls_1', [(5, 5, 7, 5), (7, 5, 7, 7)]), '',
                  pose(0, 0, 0), 'world')
    out['spawn_walls'] = [r.success, r.status_message]
    r = spawn_sdf('lamp_1', LIGHT, '', pose(1, 0, 0), 'world')
    out['spawn_light_dup'] = [r.success, r.status_message]
    r = svc('/gazebo/get_light_properties', gs.GetLightProperties)('lamp_1')
    out['light_props'] = [r.success, r.diffuse.r]
    # move the box (Gazebo's translate tool ends in a set_model_state)
    ms = ModelState(model_name='box_a', pose=pose(3, 3, 0.15, 0.258819, 0.9659258),
                    reference_frame='world')
    r = svc('/gazebo/set_model_state', gs.SetModelState)(ms)
    out['move'] = [r.success, r.status_message]
    # turn the robot's joint
    r = svc('/gazebo/set_model_configuration', gs.SetModelConfiguration)(
        'arm', '', ['shoulder'], [0.6])
    out['config'] = [r.success, r.status_message]
    # delete the world's own cone
    r = svc('/gazebo/delete_model', gs.DeleteModel)('cone_world')
    out['delete'] = [r.success, r.status_message]
    # stepping a running world is refused
    r = step(5)
    out['step_running'] = [r.success, r.status_message]
    svc('/gazebo/pause_physics', Empty)()
    time.sleep(0.3)                     # the step in progress, if any, ends
    s0 = stats()
    t0 = svc('/gazebo/get_world_properties', gs.GetWorldProperties)().sim_time
    r = step(100)
    out['step'] = [r.success, r.status_message, r.sim_time, r.iterations]
    out['t0'] = t0
    out['t1'] = svc('/gazebo/get_world_properties', gs.GetWorldProperties)().sim_time
    phys = svc('/gazebo/get_physics_properties', gs.GetPhysicsProperties)()
    out['step_size'] = phys.time_step
    # the statistics after the steps (the first message whose iterations include them)
    deadline = time.monotonic() + 60
    s1 = stats()
    while s1.iterations < r.iterations and time.monotonic() < deadline:
        s1 = stats()
    out['stats0'] = {'iterations': s0.iterations, 'paused': s0.paused}
    out['stats1'] = {'iterations': s1.iterations, 'paused': s1.paused,
                     'sim_time': s1.sim_time.to_sec(), 'rtf': s1.real_time_factor,
                     'max_step_size': s1.max_step_size, 'real_time': s1.real_time.to_sec(),
                     'pause_time': s1.pause_time.to_sec()}
    # Save World As
    res = svc('/gazebo/get_world_sdf', GetWorldSDF)()
    out['sdf'] = [res.success, res.status_message]
    with open(saved_file, 'w') as f:
        f.write(res.sdf)
    out['state'] = state()
    out['control_joints'] = control_joints()
    return out


def main(argv):
    rospy.init_node('world_control_client', anonymous=True)
    if argv[1] == 'edit':
        out = edit(argv[2])
    elif argv[1] == 'arm_urdf':
        print(ARM)
        return
    else:
        out = state()
        out['control_joints'] = control_joints()
    print(json.dumps(out))


if __name__ == '__main__':
    main(rospy.myargv(sys.argv))
