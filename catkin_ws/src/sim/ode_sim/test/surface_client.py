#!/usr/bin/env python3
"""A client of a running sim_node for test_gazebo_ros_surface.py: `surface_client.py MODE`
runs one scenario as a user would (services, topics, dynamic_reconfigure) and prints one JSON
object of what it saw; the test asserts on it."""
import json
import math
import sys
import time

import rosgraph
import rospy
from gazebo_msgs import msg as gm
from gazebo_msgs import srv as gs
from geometry_msgs.msg import Point, Pose, Quaternion
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Empty

ROBOT = """<?xml version="1.0"?>
<robot name="arm">
  <link name="base"><inertial><mass value="50"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial>
    <collision><geometry><box size="0.4 0.4 0.2"/></geometry></collision></link>
  <link name="arm"><inertial><origin xyz="0.25 0 0"/><mass value="0.5"/>
      <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
    <collision><origin xyz="0.25 0 0"/><geometry><box size="0.5 0.05 0.05"/></geometry></collision></link>
  <joint name="shoulder" type="continuous"><parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.3"/><axis xyz="0 0 1"/></joint>
</robot>"""

BOX = """<?xml version="1.0"?>
<sdf version="1.6"><model name="box"><link name="link">
  <inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial>
  <collision name="c"><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision>
</link></model></sdf>"""


def svc(name, typ):
    rospy.wait_for_service(name, timeout=60)
    return rospy.ServiceProxy(name, typ)


def pose(x, y, z):
    return Pose(Point(x, y, z), Quaternion(0, 0, 0, 1))


def sim_time():
    return svc('/gazebo/get_world_properties', gs.GetWorldProperties)().sim_time


def run_until(t_end, timeout=120.0):
    """Unpause, wait until sim time reaches t_end, pause again."""
    svc('/gazebo/unpause_physics', Empty)()
    deadline = time.monotonic() + timeout
    while sim_time() < t_end:
        if time.monotonic() > deadline:
            raise SystemExit('sim time did not reach %g' % t_end)
        time.sleep(0.02)
    svc('/gazebo/pause_physics', Empty)()


def step_to(t_end):
    """Pause and run exactly the steps that bring sim time to t_end (/gazebo/step_world): the
    sim time a reading is taken at is counted in steps, never raced against the wall clock."""
    from ode_sim_msgs.srv import StepWorld
    svc('/gazebo/pause_physics', Empty)()
    dt = svc('/gazebo/get_physics_properties', gs.GetPhysicsProperties)().time_step
    n = int(math.ceil((t_end - sim_time()) / dt - 1e-6))
    if n > 0:
        r = svc('/gazebo/step_world', StepWorld)(n)
        if not r.success:
            raise SystemExit(r.status_message)


def graph():
    """Topics published, topics subscribed, services (all nodes) as the master sees them."""
    pubs, subs, srvs = rosgraph.Master('/surface_client').getSystemState()
    return ({t: sorted(n) for t, n in pubs}, {t: sorted(n) for t, n in subs},
            {s: sorted(n) for s, n in srvs})


def wait_clock():
    rospy.wait_for_message('/clock', Clock, timeout=60)


def mode_graph():
    """What the simulator advertises, then /gazebo/scene_markers once subscribed."""
    wait_clock()
    time.sleep(2.0)     # the simulator has set up everything it would
    pubs, _subs, srvs = graph()
    out = {'topics': sorted(t for t, n in pubs.items() if '/gazebo' in n),
           'services': sorted(s for s, n in srvs.items() if '/gazebo' in n)}
    if '--markers' in sys.argv:
        from visualization_msgs.msg import MarkerArray
        got = []
        rospy.Subscriber('/gazebo/scene_markers', MarkerArray, got.append)
        deadline = time.monotonic() + 60
        while not got and time.monotonic() < deadline:
            time.sleep(0.1)
        out['markers'] = len(got[0].markers) if got else None
    if '--metrics' in sys.argv:
        m = rospy.wait_for_message('/gazebo/performance_metrics', gm.PerformanceMetrics,
                                   timeout=60)
        out['metrics'] = [m.real_time_factor, m.header.stamp.to_sec(), len(m.sensors)]
    return out


def mode_services():
    out = {}
    spawn = svc('/gazebo/spawn_urdf_model', gs.SpawnModel)
    spawn_sdf = svc('/gazebo/spawn_sdf_model', gs.SpawnModel)
    out['spawn'] = spawn('arm', ROBOT, '', pose(0, 0, 0.1), '').success
    out['spawn_box'] = spawn_sdf('box', BOX, '', pose(2, 0, 1.0), '').success
    _lights(out)
    _links(out)
    _joints_and_wrenches(out)
    _world_and_ghosts(out)
    return out


def _lights(out):
    """get/set_light_properties, delete_light."""
    get_light = svc('/gazebo/get_light_properties', gs.GetLightProperties)
    r = get_light('sun')
    out['sun'] = [r.success, [r.diffuse.r, r.diffuse.g, r.diffuse.b, r.diffuse.a],
                  [r.attenuation_constant, r.attenuation_linear, r.attenuation_quadratic]]
    r = get_light('moon')
    out['moon'] = [r.success, r.status_message]
    req = gs.SetLightPropertiesRequest(light_name='sun')
    req.diffuse.r, req.diffuse.g, req.diffuse.b, req.diffuse.a = 0.5, 0.4, 0.3, 1.0
    req.attenuation_constant, req.attenuation_linear, req.attenuation_quadratic = 0.5, 0.1, 0.01
    r = svc('/gazebo/set_light_properties', gs.SetLightProperties)(req)
    out['set_sun'] = r.success
    r = get_light('sun')
    out['sun_after'] = [[r.diffuse.r, r.diffuse.g, r.diffuse.b],
                        [r.attenuation_constant, r.attenuation_linear, r.attenuation_quadratic]]
    req.light_name = 'moon'
    r = svc('/gazebo/set_light_properties', gs.SetLightProperties)(req)
    out['set_moon'] = [r.success, r.status_message]
    delete_light = svc('/gazebo/delete_light', gs.DeleteLight)
    r = delete_light('sun')
    out['delete_sun'] = [r.success, r.status_message]
    out['sun_gone'] = get_light('sun').success
    r = delete_light('sun')
    out['delete_again'] = [r.success, r.status_message]


def _links(out):
    """get/set_link_properties."""
    get_link = svc('/gazebo/get_link_properties', gs.GetLinkProperties)
    r = get_link('arm::arm')
    out['arm_link'] = [r.success, r.mass, [r.com.position.x, r.com.position.y,
                                           r.com.position.z], r.ixx, r.iyy, r.gravity_mode]
    r = get_link('nowhere::link')
    out['no_link'] = [r.success, r.status_message]
    r = get_link('box::link')
    set_link = svc('/gazebo/set_link_properties', gs.SetLinkProperties)
    r = set_link('box::link', r.com, False, 2.0, 0.02, 0, 0, 0.02, 0, 0.02)
    out['set_box'] = [r.success, r.status_message]
    r = get_link('box::link')
    out['box_after'] = [r.mass, r.gravity_mode, r.ixx]
    r = set_link('nowhere::link', Pose(), True, 1, 0, 0, 0, 0, 0, 0)
    out['set_no_link'] = [r.success, r.status_message]


def _joints_and_wrenches(out):
    """Joint efforts in a sim-time window, a body wrench, clear_joint_forces,
    set_joint_properties."""
    get_joint = svc('/gazebo/get_joint_properties', gs.GetJointProperties)
    r = get_joint('elbow')
    out['no_joint'] = [r.success, r.status_message]
    t0 = sim_time()
    apply = svc('/gazebo/apply_joint_effort', gs.ApplyJointEffort)
    r = apply('shoulder', 0.1, rospy.Time.from_sec(t0 + 1.0), rospy.Duration.from_sec(0.2))
    out['apply'] = [r.success, r.status_message]
    r = apply('elbow', 0.1, rospy.Time(0), rospy.Duration(1))
    out['apply_missing'] = [r.success, r.status_message]
    step_to(t0 + 0.9)
    r = get_joint('shoulder')
    out['before_window'] = [r.success, r.type, r.position[0], r.rate[0], r.status_message]
    step_to(t0 + 1.5)
    r = get_joint('shoulder')
    out['after_window'] = [r.position[0], r.rate[0], sim_time() - t0]
    box = svc('/gazebo/get_model_state', gs.GetModelState)('box', '')
    out['box_z'] = box.pose.position.z        # no gravity: still at 1.0
    # a wrench on the floating box: force at the centre of mass, point x force as torque
    from geometry_msgs.msg import Point, Wrench
    w = Wrench()
    w.force.x = 1.0
    t2 = sim_time()
    r = svc('/gazebo/apply_body_wrench', gs.ApplyBodyWrench)(
        'box::link', '', Point(0, 1, 0), w, rospy.Time(0), rospy.Duration.from_sec(0.1))
    out['wrench'] = [r.success, r.status_message]
    r = svc('/gazebo/apply_body_wrench', gs.ApplyBodyWrench)(
        'nothing::link', '', Point(), w, rospy.Time(0), rospy.Duration(1))
    out['wrench_missing'] = [r.success, r.status_message]
    step_to(t2 + 0.3)
    box = svc('/gazebo/get_model_state', gs.GetModelState)('box', '')
    out['box_twist'] = [box.twist.linear.x, box.twist.angular.z]
    # a forever effort, cleared
    t1 = sim_time()
    apply('shoulder', 0.1, rospy.Time(0), rospy.Duration(-1))
    step_to(t1 + 0.2)
    svc('/gazebo/clear_joint_forces', gs.JointRequest)('shoulder')
    r1 = get_joint('shoulder').rate[0]
    step_to(sim_time() + 0.2)
    out['cleared'] = [r1, get_joint('shoulder').rate[0]]
    # set_joint_properties: the joint motor drives it at vel with fmax
    cfg = gm.ODEJointProperties(vel=[-1.0], fmax=[10.0])
    r = svc('/gazebo/set_joint_properties', gs.SetJointProperties)('shoulder', cfg)
    out['set_joint'] = [r.success, r.status_message]
    step_to(sim_time() + 0.3)
    out['motor_rate'] = get_joint('shoulder').rate[0]


def _world_and_ghosts(out):
    """get_world_properties, get_physics_properties, a missing model."""
    r = svc('/gazebo/get_world_properties', gs.GetWorldProperties)()
    out['world'] = [r.sim_time, r.rendering_enabled, sorted(r.model_names), r.success,
                    r.status_message]
    r = svc('/gazebo/get_physics_properties', gs.GetPhysicsProperties)()
    o = r.ode_config
    out['physics'] = [r.time_step, r.max_update_rate, r.pause, r.gravity.z,
                      o.auto_disable_bodies, o.sor_pgs_precon_iters, o.sor_pgs_iters,
                      o.sor_pgs_w, o.contact_surface_layer, o.contact_max_correcting_vel,
                      o.cfm, o.erp, o.max_contacts, r.success, r.status_message]
    r = svc('/gazebo/delete_model', gs.DeleteModel)('ghost')
    out['delete_ghost'] = [r.success, r.status_message]
    r = svc('/gazebo/get_model_state', gs.GetModelState)('ghost', '')
    out['state_ghost'] = [r.success, r.status_message]


def mode_paused_markers():
    """Paused from the start: a box spawned from a window reaches /gazebo/scene_markers without
    a single step (sim time stays 0)."""
    from visualization_msgs.msg import MarkerArray
    wait_clock()
    arrays = []
    rospy.Subscriber('/gazebo/scene_markers', MarkerArray, arrays.append)
    deadline = time.monotonic() + 60
    while not arrays and time.monotonic() < deadline:
        time.sleep(0.05)
    before = len(arrays)
    box = BOX.replace('<model name="box">', '<model name="pbox">').replace(
        '</collision>', '</collision><visual name="v"><geometry><box><size>0.2 0.2 0.2</size>'
                        '</box></geometry></visual>')
    spawn = svc('/gazebo/spawn_sdf_model', gs.SpawnModel)
    res = spawn(model_name='pbox', model_xml=box, initial_pose=pose(1, 0, 0.1))
    assert res.success, res.status_message

    def seen():
        return any(m.ns.endswith('/pbox') for a in arrays[before:] for m in a.markers)
    while not seen() and time.monotonic() < deadline + 60:
        time.sleep(0.05)
    props = svc('/gazebo/get_world_properties', gs.GetWorldProperties)()
    return {'first_array': before > 0, 'seen': seen(), 'sim_time': props.sim_time}


def mode_reconfigure():
    """rqt_reconfigure's path: dynamic_reconfigure's client on /gazebo."""
    from dynamic_reconfigure.client import Client
    out = {}
    wait_clock()
    spawn_sdf = svc('/gazebo/spawn_sdf_model', gs.SpawnModel)
    spawn_sdf('box', BOX, '', pose(0, 0, 50.0), '')
    client = Client('/gazebo', timeout=60)
    cfg = client.get_configuration(timeout=60)
    out['initial'] = {k: cfg[k] for k in ('time_step', 'max_update_rate', 'gravity_z',
                                          'sor_pgs_iters', 'max_contacts')}
    clock = []
    rospy.Subscriber('/clock', Clock, lambda m: clock.append(m.clock.to_sec()))
    time.sleep(1.0)
    new = client.update_configuration({'time_step': 0.002, 'gravity_z': -3.0,
                                       'sor_pgs_iters': 30})
    out['returned'] = [new['time_step'], new['gravity_z'], new['sor_pgs_iters']]
    r = svc('/gazebo/get_physics_properties', gs.GetPhysicsProperties)()
    out['physics'] = [r.time_step, r.gravity.z, r.ode_config.sor_pgs_iters]
    out['param'] = rospy.get_param('/gazebo/time_step')
    # free fall under the new gravity, from the box's state at two times (paused reads)
    gms = svc('/gazebo/get_model_state', gs.GetModelState)
    svc('/gazebo/pause_physics', Empty)()
    s1, t1 = gms('box', ''), sim_time()
    run_until(t1 + 0.5)
    s2, t2 = gms('box', ''), sim_time()
    dt = t2 - t1
    out['fall'] = [s1.pose.position.z, s1.twist.linear.z, s2.pose.position.z, dt]
    svc('/gazebo/unpause_physics', Empty)()
    time.sleep(1.0)
    out['clock_monotonic'] = all(b >= a for a, b in zip(clock, clock[1:]))
    out['clock_n'] = len(clock)
    r = client.update_configuration({'time_step': 0.0})
    out['zero_step'] = [r['time_step'],
                        svc('/gazebo/get_physics_properties',
                            gs.GetPhysicsProperties)().time_step]
    return out


def main():
    rospy.init_node('surface_client', anonymous=True)
    mode = sys.argv[1]
    out = {'graph': mode_graph, 'services': mode_services, 'paused_markers': mode_paused_markers,
           'reconfigure': mode_reconfigure}[mode]()
    print(json.dumps(out))


if __name__ == '__main__':
    main()
