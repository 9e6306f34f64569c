"""gazebo_plugins beyond the course's first ones, each in an SDF world with the original's tags,
driven from a client process as a user would, and checked against the simulated truth:
range (a wall at known distances), planar_move and p3d (the model's state), force (the
acceleration F/m), vacuum gripper (holds a box only while on)."""
import json
import os
import subprocess

import pytest

from course_testing import Proc

HERE = os.path.dirname(os.path.abspath(__file__))

WORLD = """<?xml version="1.0"?>
<sdf version="1.6">
  <world name="default">
    <include><uri>model://ground_plane</uri></include>
    <include><uri>model://sun</uri></include>
    {models}
  </world>
</sdf>
"""

BOX_LINK = """<link name="{link}">{extra}
  <inertial><mass>{mass}</mass><inertia><ixx>{i}</ixx><iyy>{i}</iyy><izz>{i}</izz></inertia></inertial>
  <collision name="c"><geometry><box><size>{size}</size></box></geometry></collision>
  <visual name="v"><geometry><box><size>{size}</size></box></geometry></visual>
  {sensors}
</link>"""


def box_link(link='link', mass=1.0, size='0.2 0.2 0.2', extra='', sensors='', i=0.01):
    return BOX_LINK.format(link=link, mass=mass, size=size, extra=extra, sensors=sensors, i=i)


def sonar_sensor(name, radiation, hfov=0.2):
    tag = '<radiation>%s</radiation>' % radiation if radiation else ''
    return """<sensor type="ray" name="{n}">
  <update_rate>20</update_rate>
  <ray><scan>
    <horizontal><samples>5</samples><resolution>1</resolution><min_angle>-{h}</min_angle><max_angle>{h}</max_angle></horizontal>
    <vertical><samples>3</samples><resolution>1</resolution><min_angle>-{h}</min_angle><max_angle>{h}</max_angle></vertical>
  </scan><range><min>0.02</min><max>4.0</max><resolution>0.01</resolution></range></ray>
  <plugin name="{n}_plugin" filename="libgazebo_ros_range.so">
    <gaussianNoise>0.0</gaussianNoise>
    <alwaysOn>true</alwaysOn>
    <updateRate>20</updateRate>
    <topicName>/{n}/range</topicName>
    <frameName>{n}_link</frameName>
    {tag}
    <fov>{fov}</fov>
  </plugin>
</sensor>""".format(n=name, h=hfov / 2, tag=tag, fov=hfov)


RANGE_MODELS = """
<model name="wall"><pose>2.1 0 0.5 0 0 0</pose>
  {wall}
</model>
<model name="sonar"><static>true</static><pose>0 0 0.5 0 0 0</pose>
  {sonar}
</model>
<model name="ir"><static>true</static><pose>0 3 0.5 0 0 3.14159</pose>
  {ir}
</model>
""".format(wall=box_link(mass=50.0, size='0.2 4 1', i=10.0),
           sonar=box_link(size='0.02 0.02 0.02', sensors=sonar_sensor('sonar', 'ultrasound')),
           ir=box_link(size='0.02 0.02 0.02', sensors=sonar_sensor('ir', 'infrared')))

PLANAR_MODELS = """
<model name="mover"><pose>0 0 0.5 0 0 0</pose>
  {link}
  <plugin name="object_controller" filename="libgazebo_ros_planar_move.so">
    <commandTopic>cmd_vel</commandTopic>
    <odometryTopic>odom</odometryTopic>
    <odometryFrame>odom</odometryFrame>
    <odometryRate>20.0</odometryRate>
    <robotBaseFrame>base_footprint</robotBaseFrame>
  </plugin>
  <plugin name="p3d" filename="libgazebo_ros_p3d.so">
    <alwaysOn>true</alwaysOn>
    <updateRate>50.0</updateRate>
    <bodyName>link</bodyName>
    <topicName>/mover/ground_truth</topicName>
    <gaussianNoise>0.0</gaussianNoise>
    <frameName>world</frameName>
  </plugin>
</model>
""".format(link=box_link(mass=10.0, i=0.1, extra='<gravity>false</gravity>'))

FORCE_MODELS = """
<model name="puck"><pose>0 0 1.0 0 0 0</pose>
  {link}
  <plugin name="push" filename="libgazebo_ros_force.so">
    <bodyName>link</bodyName>
    <topicName>push</topicName>
  </plugin>
</model>
""".format(link=box_link(mass=0.5, extra='<gravity>false</gravity>'))

GRIPPER_MODELS = """
<model name="arm"><static>true</static><pose>0 0 1.0 0 0 0</pose>
  {hand}
  <plugin name="vacuum" filename="libgazebo_ros_vacuum_gripper.so">
    <robotNamespace>/gripper</robotNamespace>
    <bodyName>hand</bodyName>
    <topicName>grasping</topicName>
    <maxForce>50</maxForce>
  </plugin>
</model>
<model name="parcel"><pose>0 0 0.96 0 0 0</pose>
  {parcel}
</model>
""".format(hand=box_link(link='hand', size='0.05 0.05 0.02'),
           parcel=box_link(mass=0.5, size='0.05 0.05 0.05', i=0.001))


BLOCK_SENSOR = """<sensor type="ray" name="block">
  <update_rate>10</update_rate>
  <ray><scan>
    <horizontal><samples>5</samples><resolution>1</resolution><min_angle>-0.3</min_angle><max_angle>0.3</max_angle></horizontal>
    <vertical><samples>3</samples><resolution>1</resolution><min_angle>-0.2</min_angle><max_angle>0.2</max_angle></vertical>
  </scan><range><min>0.05</min><max>6.0</max><resolution>0.01</resolution></range></ray>
  <plugin name="block_laser" filename="libgazebo_ros_block_laser.so">
    <topicName>/block/cloud</topicName>
    <frameName>block_link</frameName>
    <gaussianNoise>0.0</gaussianNoise>
  </plugin>
</sensor>"""

BLOCK_MODELS = """
<model name="wall"><static>true</static><pose>2.1 0 1 0 0 0</pose>
  <link name="link"><collision name="c"><geometry><box><size>0.2 8 2</size></box></geometry></collision></link>
</model>
<model name="scanner"><static>true</static><pose>0 0 1 0 0 0</pose>
  {link}
</model>
""".format(link=box_link(size='0.02 0.02 0.02', sensors=BLOCK_SENSOR))

TRAJECTORY_MODELS = """
<model name="turret"><pose>1 1 0.1 0 0 0</pose>
  {base}
  {top}
  <joint name="anchor" type="fixed"><parent>world</parent><child>link</child></joint>
  <joint name="swivel" type="revolute"><parent>link</parent><child>top</child>
    <pose>0 0 0 0 0 0</pose>
    <axis><xyz>0 0 1</xyz><limit><lower>-3</lower><upper>3</upper></limit></axis></joint>
  <plugin name="trajectory" filename="libgazebo_ros_joint_pose_trajectory.so">
    <topicName>set_joint_trajectory</topicName>
    <updateRate>100</updateRate>
  </plugin>
</model>
""".format(base=box_link(), top=box_link(link='top', size='0.5 0.05 0.05',
                                         extra='<pose>0 0 0.2 0 0 0</pose>'))


TRIGGERED_SENSOR = """<sensor type="camera" name="cam">
  <update_rate>30</update_rate>
  <camera><horizontal_fov>1.0</horizontal_fov><image><width>64</width><height>48</height>
    <format>R8G8B8</format></image><clip><near>0.05</near><far>50</far></clip></camera>
  <plugin name="cam_plugin" filename="libgazebo_ros_triggered_camera.so">
    <cameraName>cam</cameraName>
    <imageTopicName>image_raw</imageTopicName>
    <cameraInfoTopicName>camera_info</cameraInfoTopicName>
    <frameName>cam_link</frameName>
  </plugin>
</sensor>"""

TRIGGERED_MODELS = """
<model name="camera"><static>true</static><pose>0 0 1 0 0 0</pose>
  {link}
</model>
""".format(link=box_link(size='0.02 0.02 0.02', sensors=TRIGGERED_SENSOR))


STEREO_CAMERA = """<camera name="{n}"><pose>0 {y} 0 0 0 0</pose>
      <horizontal_fov>1.0</horizontal_fov><image><width>160</width><height>120</height>
      <format>R8G8B8</format></image><clip><near>0.05</near><far>50</far></clip></camera>"""

STEREO_MODELS = """
<model name="post"><static>true</static><pose>2.0 0 1 0 0 0</pose>
  <link name="link"><visual name="v"><geometry><box><size>0.1 0.1 2</size></box></geometry>
    <material><ambient>1 0 0 1</ambient><diffuse>1 0 0 1</diffuse></material></visual></link>
</model>
<model name="stereo_rig"><static>true</static><pose>0 0 1 0 0 0</pose>
  <link name="link">
    <sensor type="multicamera" name="stereo">
      <update_rate>10</update_rate>
      {left}
      {right}
      <plugin name="stereo_plugin" filename="libgazebo_ros_multicamera.so">
        <cameraName>stereo</cameraName>
        <imageTopicName>image_raw</imageTopicName>
        <cameraInfoTopicName>camera_info</cameraInfoTopicName>
        <frameName>stereo_link</frameName>
        <hackBaseline>0.07</hackBaseline>
      </plugin>
    </sensor>
  </link>
</model>
""".format(left=STEREO_CAMERA.format(n='left', y=0.035),
           right=STEREO_CAMERA.format(n='right', y=-0.035))


GPS_MODELS = """
<model name="rover"><pose>0 0 0.5 0 0 0</pose>
  {link}
  <plugin name="mover" filename="libgazebo_ros_planar_move.so">
    <robotNamespace>/rover</robotNamespace>
    <odometryFrame>odom</odometryFrame>
    <robotBaseFrame>base_footprint</robotBaseFrame>
    <odometryRate>20.0</odometryRate>
  </plugin>
  <plugin name="gps" filename="libhector_gazebo_ros_gps.so">
    <robotNamespace>/rover</robotNamespace>
    <bodyName>link</bodyName>
    <frameId>gps_link</frameId>
    <referenceLatitude>55.75</referenceLatitude>
    <referenceLongitude>37.62</referenceLongitude>
    <referenceAltitude>150</referenceAltitude>
    <updateRate>10</updateRate>
  </plugin>
</model>
""".format(link=box_link(mass=5.0, i=0.05, extra='<gravity>false</gravity>'))


IMU_SENSOR = """<sensor type="imu" name="imu">
  <always_on>true</always_on><update_rate>50</update_rate>
  <plugin name="imu_plugin" filename="libgazebo_ros_imu_sensor.so">
    <topicName>imu</topicName>
    <bodyName>link</bodyName>
    <updateRateHZ>50.0</updateRateHZ>
    <gaussianNoise>0.0</gaussianNoise>
    <xyzOffset>0 0 0</xyzOffset>
    <rpyOffset>0 0 0</rpyOffset>
    <frameName>imu_link</frameName>
  </plugin>
</sensor>"""

GPU_SENSOR = """<sensor type="gpu_ray" name="gpu">
  <update_rate>10</update_rate>
  <ray><scan><horizontal><samples>91</samples><resolution>1</resolution>
    <min_angle>-0.785</min_angle><max_angle>0.785</max_angle></horizontal></scan>
    <range><min>0.1</min><max>10</max><resolution>0.01</resolution></range></ray>
  <plugin name="gpu_laser" filename="libgazebo_ros_gpu_laser.so">
    <topicName>/gpu_scan</topicName>
    <frameName>gpu_link</frameName>
  </plugin>
</sensor>"""

IMU_GPU_MODELS = """
<model name="spinner"><pose>0 0 1 0 0 0</pose>
  {spinner}
</model>
<model name="wall"><static>true</static><pose>3.1 5 0.5 0 0 0</pose>
  <link name="link"><collision name="c"><geometry><box><size>0.2 4 1</size></box></geometry></collision></link>
</model>
<model name="lidar"><static>true</static><pose>0 5 0.5 0 0 0</pose>
  {lidar}
</model>
""".format(spinner=box_link(mass=1.0, extra='<gravity>false</gravity>', sensors=IMU_SENSOR),
           lidar=box_link(size='0.02 0.02 0.02', sensors=GPU_SENSOR))


def run(roscore, tmp_path, models, mode, *sim_args):
    world = tmp_path / 'w.world'
    world.write_text(WORLD.format(models=models))
    subprocess.run(['rosparam', 'set', '/use_sim_time', 'true'], env=roscore.env, check=True,
                   timeout=120)
    node = Proc(['rosrun', 'ode_sim', 'sim_node', str(world)] + list(sim_args),
                env=roscore.env, log=str(tmp_path / 'sim.log'))
    try:
        res = subprocess.run(['/usr/bin/python3', os.path.join(HERE, 'plugin_client.py'), mode],
                             env=roscore.env, capture_output=True, text=True, timeout=300)
    finally:
        node.stop()
    assert res.returncode == 0, res.stdout + res.stderr + node.output()[-4000:]
    return json.loads(res.stdout.strip().splitlines()[-1]), node.output()


def test_range_sees_the_wall_at_its_distance(roscore, tmp_path):
    out, log = run(roscore, tmp_path, RANGE_MODELS, 'range')
    rng, rmin, rmax, fov, radiation, frame = out['near']
    # the wall's near face at x = 2.0; the sonar's centre ray hits it square on
    assert rng == pytest.approx(2.0, abs=1e-3)
    assert (rmin, rmax, radiation, frame) == (pytest.approx(0.02), pytest.approx(4.0), 0,
                                              'sonar_link')
    assert fov == pytest.approx(0.2)
    assert out['moved'] == pytest.approx(1.1, abs=1e-3)
    assert out['nothing'] == pytest.approx(4.0)              # nothing within reach: max_range
    assert out['ir'] == [1, 'ir_link']                        # INFRARED
    assert 'Range plugin missing <radiation>' not in log


def test_planar_move_odometry_and_p3d_follow_the_model(roscore, tmp_path):
    out, log = run(roscore, tmp_path, PLANAR_MODELS, 'planar', '-u')
    start, end, t_end = out['start'], out['end'], out['t_end']
    dt = t_end - out['t_start']
    # the model (floating: no ground friction) moved at the commanded (0.5, 0.2) m/s, yaw 0
    assert end['vel'][:2] == pytest.approx([0.5, 0.2], abs=1e-3)
    assert end['xyz'][0] - start['xyz'][0] == pytest.approx(0.5 * dt, abs=0.01)
    assert end['xyz'][1] - start['xyz'][1] == pytest.approx(0.2 * dt, abs=0.01)
    o = out['odom']
    assert (o['frame'], o['child']) == ('odom', 'base_footprint')
    lag = t_end - o['stamp']
    assert 0 <= lag <= 0.051
    assert o['xy'] == pytest.approx([end['xyz'][0] - 0.5 * lag, end['xyz'][1] - 0.2 * lag],
                                    abs=1e-3)
    assert o['vel'] == pytest.approx([0.5, 0.2, 0.0], abs=2e-3)
    # odometry every 1/20 s and a step (the original publishes once MORE than the period passed)
    stamps = out['odom_stamps']
    gaps = [b - a for a, b in zip(stamps, stamps[1:])]
    assert all(g == pytest.approx(0.051, abs=1e-6) for g in gaps), gaps
    g = out['p3d']
    assert (g['frame'], g['child']) == ('world', 'link')
    lag = t_end - g['stamp']
    assert 0 <= lag <= 0.021
    truth = out['model_states']
    assert g['xyz'] == pytest.approx([truth[0] - 0.5 * lag, truth[1] - 0.2 * lag, truth[2]],
                                     abs=1e-3)
    assert g['vel'] == pytest.approx([0.5, 0.2], abs=1e-3)
    turned = out['turned']
    assert turned['w'] == pytest.approx(0.5, abs=1e-3)
    assert out['odom_w'] == pytest.approx(0.5, abs=0.01)
    # the original's WARN for each missing tag (here only <cmdTimeout>)
    assert 'PlanarMovePlugin (ns = ) missing <cmdTimeout>, defaults to -1.000000' in log
    assert 'PlanarMovePlugin (ns = ) missing <commandTopic>' not in log


def test_force_accelerates_by_f_over_m(roscore, tmp_path):
    out, _log = run(roscore, tmp_path, FORCE_MODELS, 'force', '-u')
    assert out['accel'] == pytest.approx(2.0 / 0.5, rel=0.01)
    v3, v4 = out['coast']
    assert v3 > 3.0 and v4 == pytest.approx(v3, abs=1e-6)    # no force: constant velocity


def test_vacuum_gripper_holds_the_box_only_while_on(roscore, tmp_path):
    out, log = run(roscore, tmp_path, GRIPPER_MODELS, 'gripper', '-u')
    assert out['held'][2] > 0.9                  # still at the hand (z = 1.0), not fallen
    assert out['grasping_on'] is True
    assert out['dropped'][2] == pytest.approx(0.025, abs=0.01)    # on the ground
    assert out['grasping_off'] is False
    assert out['out_of_reach'][2] == pytest.approx(0.025, abs=0.01)
    assert out['grasping_far'] is False
    assert 'gazebo_ros_vacuum_gripper: status: off -> on' in log


def test_block_laser_points_lie_on_the_wall(roscore, tmp_path):
    out, _log = run(roscore, tmp_path, BLOCK_MODELS, 'block')
    assert out['frame'] == 'block_link'
    pts = out['points']
    assert len(pts) == 15 and len(out['channels']) == 1 and len(out['channels'][0]) == 15
    # every ray hits the wall's face x = 2.0 (range 2 / (cos p cos y)); the original places a
    # point in the direction halfway to the next ray (yaw (ja + jb) / 2 steps, pitch likewise),
    # z mirrored
    import math
    yaws = [-0.3 + 0.15 * k for k in range(5)]
    pitches = [-0.2, 0.0, 0.2]
    expect = []
    for j in range(3):
        for i in range(5):
            r = 2.0 / (math.cos(pitches[j]) * math.cos(yaws[i]))
            y = 0.5 * (yaws[i] + yaws[min(i + 1, 4)])
            p = 0.5 * (pitches[j] + pitches[min(j + 1, 2)])
            expect.append([r * math.cos(p) * math.cos(y), r * math.cos(p) * math.sin(y),
                           -r * math.sin(p)])
    for got, want in zip(pts, expect):
        assert got == pytest.approx(want, abs=2e-3)
    assert pts[-1][0] == pytest.approx(2.0, abs=1e-3)     # the last ray: no half step


def test_joint_pose_trajectory_sets_the_joints_at_the_points_times(roscore, tmp_path):
    out, log = run(roscore, tmp_path, TRAJECTORY_MODELS, 'trajectory', '-u')
    dt = out['dt']
    assert out['rest'] == out['unstepped'] == pytest.approx(0.0, abs=1e-9)   # read, not stepped
    t1, q1 = out['first']
    assert t1 < 0.2 and q1 == pytest.approx(0.5, abs=1e-3)     # the first point at once
    # the second 0.2 s (the first point's time_from_start) after it, to the step
    th, qh = out['held']
    assert th == pytest.approx(t1 + 0.2 - dt, abs=1e-6) and qh == pytest.approx(0.5, abs=1e-3)
    t2, q2 = out['second']
    assert t2 == pytest.approx(t1 + 0.2, abs=1e-6) and q2 == pytest.approx(1.0, abs=1e-3)
    assert out['after'][1] == pytest.approx(1.0, abs=1e-3)     # the last point stays
    base, after = out['base_kept']
    assert after == pytest.approx(base, abs=1e-3)
    assert 'updating configuration [1/2]' in log


def test_triggered_camera_publishes_one_frame_per_trigger(roscore, tmp_path):
    out, _log = run(roscore, tmp_path, TRIGGERED_MODELS, 'triggered', '-u')
    assert out['before'] == 0
    assert out['counts'] == [1, 2, 3]
    stamps = out['stamps']
    assert stamps == sorted(stamps) and len(set(stamps)) == 3
    assert out['size'] == [64, 48, 'rgb8']


def test_multicamera_stereo_pair_has_the_baseline(roscore, tmp_path):
    import math
    out, _log = run(roscore, tmp_path, STEREO_MODELS, 'stereo')
    left, right = out['left'], out['right']
    f = 80.0 / math.tan(0.5)
    assert left['P'][3] == 0.0 and right['P'][3] == pytest.approx(-f * 0.07)
    assert left['frame'] == right['frame'] == 'stereo_link'
    assert left['n'] > 50 and right['n'] > 50
    # the post (front face 1.95 m away) is shifted by f B / Z between the images
    assert left['col'] - right['col'] == pytest.approx(f * 0.07 / 1.95, abs=1.0)
    assert left['col'] > 79.5 > right['col']


def test_gps_fix_follows_the_link_on_the_wgs84_ellipsoid(roscore, tmp_path):
    import math
    out, _log = run(roscore, tmp_path, GPS_MODELS, 'gps', '-u')
    lag = out['t_end'] - out['stamp']
    assert 0 <= lag <= 0.101
    x = out['end']['xyz'][0] - 1.0 * lag
    y = out['end']['xyz'][1] - 0.5 * lag
    z = out['end']['xyz'][2]
    # WGS84 radii at 55.75 deg (meridian and prime-vertical circle)
    a, f = 6378137.0, 1 / 298.257223563
    e2 = 2 * f - f * f
    s = math.sin(math.radians(55.75))
    n = a / math.sqrt(1 - e2 * s * s)
    r_north, r_east = n * (1 - e2) / (1 - e2 * s * s), n * math.cos(math.radians(55.75))
    lat, lon, alt = out['fix']
    assert lat == pytest.approx(55.75 + math.degrees(x / r_north), abs=1e-9)
    assert lon == pytest.approx(37.62 - math.degrees(y / r_east), abs=1e-9)
    assert alt == pytest.approx(150 + z, abs=1e-6)
    assert x > 2.5                                          # it did move 3 s at 1 m/s
    assert out['frame'] == 'gps_link' and out['status'] == [0, 0, 2]
    assert out['vel'] == pytest.approx([1.0, 0.5, 0.0], abs=1e-3)
    gaps = [b - a for a, b in zip(out['stamps'], out['stamps'][1:])]
    assert all(g == pytest.approx(0.1, abs=1.5e-3) for g in gaps), gaps


def test_imu_sensor_and_gpu_laser_against_the_truth(roscore, tmp_path):
    out, _log = run(roscore, tmp_path, IMU_GPU_MODELS, 'imu_gpu', '-u')
    assert 0 <= out['lag'] <= 0.021 and out['frame'] == 'imu_link' and out['n'] >= 45
    # the IMU's yaw at its stamp = the model's yaw then (0.5 rad/s)
    assert out['yaw'] == pytest.approx(out['yaw_end'] - 0.5 * out['lag'], abs=2e-3)
    assert out['w'] == pytest.approx([0, 0, 0.5], abs=1e-3)
    assert out['acc'] == pytest.approx([0, 0, 9.8], abs=0.05)   # a - g, floating: a = 0
    assert out['scan_mid'] == pytest.approx(3.0, abs=1e-3) and out['scan_frame'] == 'gpu_link'
