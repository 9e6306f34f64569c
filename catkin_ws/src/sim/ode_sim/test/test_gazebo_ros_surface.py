"""The rest of gazebo_ros' surface on sim_node, driven as a user would (roslaunch
gazebo_ros empty_world.launch, then services, topics and dynamic_reconfigure from a client
process): enable_ros_network, the topics Gazebo advertises and no others (besides the window
API of ode_sim_msgs, OURS_*), every service's
fields and status texts, efforts in a sim-time window, the physics reconfigure."""
import json
import os
import subprocess

import pytest

from course_testing import Proc

HERE = os.path.dirname(os.path.abspath(__file__))

GAZEBO_TOPICS = ['/clock', '/gazebo/link_states', '/gazebo/model_states',
                 '/gazebo/parameter_descriptions', '/gazebo/parameter_updates',
                 '/gazebo/performance_metrics', '/rosout']
GAZEBO_SERVICES = [
    'apply_body_wrench', 'apply_joint_effort', 'clear_body_wrenches', 'clear_joint_forces',
    'delete_light', 'delete_model', 'get_joint_properties', 'get_light_properties',
    'get_link_properties', 'get_link_state', 'get_loggers', 'get_model_properties',
    'get_model_state', 'get_physics_properties', 'get_world_properties', 'pause_physics',
    'reset_simulation', 'reset_world', 'set_joint_properties', 'set_light_properties',
    'set_link_properties', 'set_link_state', 'set_logger_level', 'set_model_configuration',
    'set_model_state', 'set_parameters', 'set_physics_properties', 'spawn_sdf_model',
    'spawn_urdf_model', 'unpause_physics']
# what gzclient gets from gzserver over Gazebo transport (ros/world_control.py, ode_sim_msgs)
OURS_TOPICS = ['/gazebo/pose_info', '/gazebo/world_stats']
OURS_SERVICES = ['get_world_sdf', 'step_world']


def launch(roscore, tmp_path, *args):
    return Proc(['roslaunch', 'gazebo_ros', 'empty_world.launch', 'gui:=false'] + list(args),
                env=roscore.env, log=str(tmp_path / 'launch.log'))


def client(roscore, proc, *args, timeout=300):
    res = subprocess.run(['/usr/bin/python3', os.path.join(HERE, 'surface_client.py')]
                         + list(args), env=roscore.env, capture_output=True, text=True,
                         timeout=timeout)
    assert res.returncode == 0, res.stdout + res.stderr + proc.output()[-4000:]
    return json.loads(res.stdout.strip().splitlines()[-1])


def test_enable_ros_network_false_leaves_only_clock(roscore, tmp_path):
    p = launch(roscore, tmp_path, 'enable_ros_network:=false')
    try:
        out = client(roscore, p, 'graph')
    finally:
        p.stop()
    assert out['topics'] == ['/clock', '/rosout']
    assert out['services'] == ['/gazebo/get_loggers', '/gazebo/set_logger_level']
    assert 'ROS gazebo topics/services are disabled' in p.output()


def test_topics_and_services_are_gazebos_and_scene_markers_come_when_subscribed(
        roscore, tmp_path):
    p = launch(roscore, tmp_path)
    try:
        out = client(roscore, p, 'graph', '--markers', '--metrics')
    finally:
        p.stop()
    # no /tf, no /gazebo/scene_markers
    assert out['topics'] == sorted(GAZEBO_TOPICS + OURS_TOPICS)
    assert out['services'] == ['/gazebo/' + s for s in sorted(GAZEBO_SERVICES + OURS_SERVICES)]
    assert out['markers'] >= 2                     # DELETEALL + the ground plane
    rtf, stamp, _sensors = out['metrics']          # paced at 1000 steps of 1 ms per second
    assert 0 < rtf <= 1.1 and stamp > 0


def test_scene_markers_parameter_advertises_them_at_once(roscore, tmp_path):
    p = launch(roscore, tmp_path, 'scene_markers:=true')
    try:
        out = client(roscore, p, 'graph')
    finally:
        p.stop()
    assert '/gazebo/scene_markers' in out['topics']


def test_scene_markers_follow_a_spawn_while_paused(roscore, tmp_path):
    p = launch(roscore, tmp_path, 'paused:=true', 'scene_markers:=true')
    try:
        out = client(roscore, p, 'paused_markers')
    finally:
        p.stop()
    assert out == {'first_array': True, 'seen': True, 'sim_time': 0.0}


def test_services_answer_with_gazebos_fields_and_texts(roscore, tmp_path):
    p = launch(roscore, tmp_path, 'paused:=true')
    try:
        out = client(roscore, p, 'services')
    finally:
        p.stop()
    assert out['spawn'] and out['spawn_box']
    # lights: empty.world's sun (model://sun)
    assert out['sun'] == [True, pytest.approx([0.8, 0.8, 0.8, 1.0]),
                          pytest.approx([0.9, 0.01, 0.001])]
    assert out['moon'] == [False, 'getLightProperties: Requested light moon not found!']
    assert out['set_sun'] is True
    assert out['sun_after'] == [pytest.approx([0.5, 0.4, 0.3]), pytest.approx([0.5, 0.1, 0.01])]
    assert out['set_moon'] == [False, 'setLightProperties: Requested light moon not found!']
    assert out['delete_sun'] == [True, 'DeleteLight: sun successfully deleted']
    assert out['sun_gone'] is False
    assert out['delete_again'] == [False, 'DeleteLight: Requested light sun not found!']
    # links
    assert out['arm_link'] == [True, 0.5, pytest.approx([0.25, 0, 0]), pytest.approx(0.001),
                               pytest.approx(0.01), True]
    assert out['no_link'] == [False, 'GetLinkProperties: link not found, did you forget to '
                                     'scope the link by model name?']
    assert out['set_box'] == [True, 'SetLinkProperties: properties set']
    assert out['box_after'] == [2.0, False, pytest.approx(0.02)]
    assert out['set_no_link'][0] is False
    assert out['box_z'] == pytest.approx(1.0, abs=1e-3)     # gravity off: it stays in the air
    # 1 N along x at the centre of mass for 0.1 s (101 steps), torque (0,1,0) x (1,0,0) = -z
    assert out['wrench'] == [True, '']
    assert out['wrench_missing'] == [False, 'ApplyBodyWrench: body does not exist']
    vx, wz = out['box_twist']
    assert vx == pytest.approx(1.0 * 0.101 / 2.0, rel=0.03)
    assert wz == pytest.approx(-1.0 * 0.101 / 0.02, rel=0.03)
    # joints; the effort acts only inside its sim-time window [t0 + 1.0, t0 + 1.2]
    assert out['no_joint'] == [False, 'GetJointProperties: joint not found']
    assert out['apply'] == [True, 'ApplyJointEffort: effort set']
    assert out['apply_missing'] == [False, 'ApplyJointEffort: joint not found']
    ok, jtype, pos, rate, msg = out['before_window']
    assert ok and jtype == 1 and msg == 'GetJointProperties: got properties'   # CONTINUOUS
    assert pos == pytest.approx(0, abs=1e-6) and rate == pytest.approx(0, abs=1e-6)
    # 0.1 N m over 0.2 s (201 steps) on the arm's 0.01 + 0.5 * 0.25^2 kg m^2 about the axis
    expect = 0.1 * 0.201 / (0.01 + 0.5 * 0.25 ** 2)
    assert out['after_window'][1] == pytest.approx(expect, rel=0.1)
    # the angle: half the window at the mean rate, then coasting from t0 + 1.2 on
    pos, rate, t_read = out['after_window']
    assert pos == pytest.approx(rate * (t_read - 1.1), abs=0.005)
    r1, r2 = out['cleared']
    assert r1 > out['after_window'][1] + 0.3 and r2 == pytest.approx(r1, rel=0.05)
    assert out['set_joint'] == [True, 'SetJointProperties: properties set']
    assert out['motor_rate'] == pytest.approx(-1.0, abs=0.02)
    sim_t, rendering, names, ok, msg = out['world']
    assert sim_t > 2.0 and rendering is True and ok
    assert names == ['arm', 'box', 'ground_plane'] and msg == 'GetWorldProperties: got properties'
    assert out['physics'] == [0.001, 1000.0, True, -9.8, False, 0, 50, 1.3, 0.001, 100.0, 0.0,
                              0.2, 20, True, 'GetPhysicsProperties: got properties']
    assert out['delete_ghost'] == [False, 'DeleteModel: model does not exist']
    assert out['state_ghost'] == [False, 'GetModelState: model does not exist']


def test_physics_reconfigure_changes_step_and_gravity_live(roscore, tmp_path):
    p = launch(roscore, tmp_path)
    try:
        out = client(roscore, p, 'reconfigure')
    finally:
        p.stop()
    assert out['initial'] == {'time_step': 0.001, 'max_update_rate': 1000.0, 'gravity_z': -9.8,
                              'sor_pgs_iters': 50, 'max_contacts': 20}
    assert out['returned'] == [0.002, -3.0, 30]
    assert out['physics'] == [0.002, -3.0, 30]
    assert out['param'] == 0.002
    z1, vz1, z2, dt = out['fall']
    # steps of 2 ms: a whole number of them, and the fall under -3 m/s^2
    assert round(dt / 0.002) == pytest.approx(dt / 0.002, abs=1e-6)
    assert z2 == pytest.approx(z1 + vz1 * dt - 1.5 * dt * dt, abs=3e-3)
    assert out['clock_monotonic'] and out['clock_n'] > 10
    assert out['zero_step'] == [0.002, 0.002]        # refused: the step in use is kept
