#!/usr/bin/env python3
"""A /gazebo API client used by test_sim_node.py: runs a scenario against a running sim_node
and prints one JSON object of observations (the test asserts on them)."""
import json
import sys
import time

import rospy
from gazebo_msgs import msg as gm
from gazebo_msgs import srv as gs
from geometry_msgs.msg import Point, Pose, Quaternion, Twist, Vector3, Wrench
from std_srvs.srv import Empty

ROBOT = """<?xml version="1.0"?>
<robot name="arm">
  <link name="base"><inertial><mass value="5"/>
      <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
    <collision><geometry><box size="0.4 0.4 0.2"/></geometry></collision></link>
  <link name="arm"><inertial><origin xyz="0.25 0 0"/><mass value="0.5"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <collision><origin xyz="0.25 0 0"/><geometry><box size="0.5 0.05 0.05"/></geometry></collision></link>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.3"/><axis xyz="0 0 1"/><limit lower="-2" upper="2" effort="10" velocity="1"/></joint>
</robot>"""

ZERO_MASS = ROBOT.replace('<mass value="0.5"/>', '<mass value="0"/>')


def svc(name, typ):
    rospy.wait_for_service(name, timeout=120)   # a hang guard: a loaded machine starts slowly
    return rospy.ServiceProxy(name, typ)


def pose(x, y, z):
    return Pose(Point(x, y, z), Quaternion(0, 0, 0, 1))


def xyz(p):
    return [p.position.x, p.position.y, p.position.z]


def state(name, rel=''):
    r = svc('/gazebo/get_model_state', gs.GetModelState)(name, rel)
    return {'ok': r.success, 'msg': r.status_message, 'xyz': xyz(r.pose),
            'q': [r.pose.orientation.x, r.pose.orientation.y, r.pose.orientation.z,
                  r.pose.orientation.w],
            'lin': [r.twist.linear.x, r.twist.linear.y, r.twist.linear.z]}


def sim_time():
    return svc('/gazebo/get_world_properties', gs.GetWorldProperties)().sim_time


def wait_sim(t_end, timeout=120.0):
    """Until the running simulation reaches sim time t_end (the timeout is a hang guard): a
    state read then has had that much simulated time, however slowly the machine runs."""
    deadline = time.monotonic() + timeout
    while sim_time() < t_end:
        if time.monotonic() > deadline:
            raise SystemExit('sim time did not reach %g' % t_end)
        time.sleep(0.02)


def api():
    out = {}
    t0 = _api_spawning(out)
    _api_running(out, t0)
    _api_physics(out)
    _api_resets(out)
    return out


def _api_spawning(out):
    """Spawning while paused; returns the sim time it stands at."""
    spawn = svc('/gazebo/spawn_urdf_model', gs.SpawnModel)
    spawn_sdf = svc('/gazebo/spawn_sdf_model', gs.SpawnModel)
    # paused at start (-u): time stands still
    t0 = sim_time()
    time.sleep(0.5)
    out['paused_still'] = sim_time() == t0
    r = spawn('arm', ROBOT, '/arm_ns', pose(1, 2, 0.1), '')
    out['spawn'] = [r.success, r.status_message]
    r = spawn('arm', ROBOT, '', pose(0, 0, 0), '')
    out['spawn_dup'] = [r.success, r.status_message]
    r = spawn('zero', ZERO_MASS, '', pose(3, 0, 1), '')
    out['spawn_zero_mass'] = [r.success, r.status_message]
    r = spawn('broken', '<robot name="x"><link name="a">', '', pose(0, 0, 0), '')
    out['spawn_broken'] = [r.success, r.status_message]
    cone = open(sys.argv[2]).read()
    r = spawn_sdf('cone', cone, '', pose(-2, 0, 0), '')
    out['spawn_sdf'] = [r.success, r.status_message]
    r = spawn_sdf('cone_rel', cone, '', pose(0, 1, 0), 'cone')
    out['spawn_rel'] = [r.success, state('cone_rel')['xyz']]
    out['arm_paused'] = state('arm')
    out['world'] = svc('/gazebo/get_world_properties', gs.GetWorldProperties)().model_names
    props = svc('/gazebo/get_model_properties', gs.GetModelProperties)('arm')
    out['props'] = [props.body_names, props.joint_names, props.is_static]
    return t0


def _api_running(out, t0):
    """Running: states, configuration, set_model_state, a wrench."""
    svc('/gazebo/unpause_physics', Empty)()
    time.sleep(1.0)
    t1 = sim_time()
    out['running'] = t1 > t0
    wait_sim(t0 + 3.0)     # the arm settles: 3 s of sim time
    out['arm_settled'] = state('arm')
    out['relative'] = state('arm', 'cone')
    ms = rospy.wait_for_message('/gazebo/model_states', gm.ModelStates, timeout=10)
    out['model_states'] = list(ms.name)
    ls = rospy.wait_for_message('/gazebo/link_states', gm.LinkStates, timeout=10)
    out['link_states'] = list(ls.name)
    # configuration
    r = svc('/gazebo/set_model_configuration', gs.SetModelConfiguration)(
        'arm', '', ['shoulder'], [1.0])
    out['config'] = [r.success, r.status_message]
    link = svc('/gazebo/get_link_state', gs.GetLinkState)('arm::arm', 'arm::base')
    o = link.link_state.pose.orientation
    out['arm_link_q'] = [o.x, o.y, o.z, o.w]
    r = svc('/gazebo/set_model_configuration', gs.SetModelConfiguration)(
        'arm', '', ['elbow'], [1.0])
    out['config_bad'] = [r.success, r.status_message]
    # set_model_state (service and topic)
    ms = gm.ModelState('arm', pose(4, -1, 0.1), Twist(), 'world')
    r = svc('/gazebo/set_model_state', gs.SetModelState)(ms)
    out['set_state'] = [r.success, state('arm')['xyz']]
    r = svc('/gazebo/set_model_state', gs.SetModelState)(
        gm.ModelState('ghost', pose(0, 0, 0), Twist(), ''))
    out['set_state_ghost'] = [r.success, r.status_message]
    pub = rospy.Publisher('/gazebo/set_model_state', gm.ModelState, queue_size=1, latch=True)
    pub.publish(gm.ModelState('cone', pose(-3, 0, 0.0), Twist(), ''))
    deadline = time.monotonic() + 5
    while time.monotonic() < deadline and abs(state('cone')['xyz'][0] + 3) > 0.05:
        time.sleep(0.1)
    out['set_state_topic'] = state('cone')['xyz']
    # wrench on the cone: it gets pushed along +y
    w = Wrench(Vector3(0, 100, 0), Vector3(0, 0, 0))
    r = svc('/gazebo/apply_body_wrench', gs.ApplyBodyWrench)(
        'cone::link', '', Point(0, 0, 0.2), w, rospy.Time(0), rospy.Duration(0.2))
    out['wrench'] = r.success
    wait_sim(sim_time() + 1.0)
    out['pushed'] = state('cone')['xyz']


def _api_physics(out):
    """get/set_physics_properties: as fast as possible, a change of the step."""
    pause = svc('/gazebo/pause_physics', Empty)
    unpause = svc('/gazebo/unpause_physics', Empty)
    phys = svc('/gazebo/get_physics_properties', gs.GetPhysicsProperties)()
    out['physics'] = [phys.time_step, phys.max_update_rate, phys.gravity.z,
                      phys.ode_config.sor_pgs_iters, phys.pause]
    svc('/gazebo/set_physics_properties', gs.SetPhysicsProperties)(
        phys.time_step, 0.0, phys.gravity, phys.ode_config)
    a = sim_time()
    time.sleep(1.0)
    out['fast_running'] = sim_time() > a
    svc('/gazebo/set_physics_properties', gs.SetPhysicsProperties)(
        phys.time_step, phys.max_update_rate, phys.gravity, phys.ode_config)
    # a change of the step: simulated time accumulates (no jump, never backwards)
    pause()
    t0 = sim_time()
    svc('/gazebo/set_physics_properties', gs.SetPhysicsProperties)(
        0.004, phys.max_update_rate, phys.gravity, phys.ode_config)
    t1 = sim_time()
    unpause()
    wait_sim(t1 + 0.3)
    pause()
    t2 = sim_time()
    svc('/gazebo/set_physics_properties', gs.SetPhysicsProperties)(
        phys.time_step, phys.max_update_rate, phys.gravity, phys.ode_config)
    t3 = sim_time()
    unpause()
    out['step_change'] = [t0, t1, t2, t3]


def _api_resets(out):
    """reset_world, reset_simulation, pause again, delete_model."""
    pause = svc('/gazebo/pause_physics', Empty)
    unpause = svc('/gazebo/unpause_physics', Empty)
    before = sim_time()
    svc('/gazebo/reset_world', Empty)()
    out['reset_world'] = [state('arm')['xyz'], sim_time() >= before]
    svc('/gazebo/reset_simulation', Empty)()
    out['reset_sim_time'] = sim_time()
    pause()
    t = sim_time()
    time.sleep(0.3)
    out['paused_again'] = sim_time() == t
    unpause()
    # delete
    r = svc('/gazebo/delete_model', gs.DeleteModel)('cone_rel')
    out['delete'] = [r.success, 'cone_rel' in svc('/gazebo/get_world_properties',
                                                  gs.GetWorldProperties)().model_names]
    r = svc('/gazebo/delete_model', gs.DeleteModel)('cone_rel')
    out['delete_again'] = [r.success, r.status_message]


def main():
    rospy.init_node('sim_client', anonymous=True)
    print(json.dumps(globals()[sys.argv[1]]()))


if __name__ == '__main__':
    main()
