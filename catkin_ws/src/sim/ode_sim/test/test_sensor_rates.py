"""Sensor rates in simulated time are exact and every published message arrives: sim_node as
fast as possible (real_time_update_rate 0) with a robot carrying a 10 Hz lidar, a 100 Hz IMU
and 50 Hz diff-drive odometry; a subscriber in another process records header stamps. Before
the sensor publishers had a queue of 1, rospy dropped messages whenever its sender thread
waited for the GIL (bench/sim_rtf counted 9 % missing)."""
import json
import subprocess
import sys

import pytest

from course_testing import Proc

WORLD = """<?xml version="1.0"?>
<sdf version="1.6"><world name="default">
  <physics type="ode"><max_step_size>0.001</max_step_size>
    <real_time_update_rate>0</real_time_update_rate></physics>
  <include><uri>model://ground_plane</uri></include>
  <model name="wall"><static>true</static><pose>2 0 0.5 0 0 0</pose><link name="l">
    <collision name="c"><geometry><box><size>0.2 4 1</size></box></geometry></collision>
  </link></model>
</world></sdf>
"""


def wheel(name, y):
    return ('<link name="%s"><inertial><mass value="0.2"/><inertia ixx="1e-4" iyy="1e-4" '
            'izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial><collision><geometry><cylinder '
            'radius="0.05" length="0.03"/></geometry></collision></link>'
            '<joint name="%s_joint" type="continuous"><parent link="base_link"/><child '
            'link="%s"/><origin xyz="0 %g 0" rpy="-1.5708 0 0"/><axis xyz="0 0 1"/></joint>'
            % (name, name, name, y))


ROBOT = """<?xml version="1.0"?>
<robot name="bot">
  <link name="base_link"><inertial><mass value="2"/><inertia ixx="0.01" iyy="0.01" izz="0.01"
    ixy="0" ixz="0" iyz="0"/></inertial><collision><origin xyz="0 0 0.03"/><geometry>
    <box size="0.3 0.2 0.06"/></geometry></collision></link>
  <link name="caster"><inertial><mass value="0.1"/><inertia ixx="1e-5" iyy="1e-5" izz="1e-5"
    ixy="0" ixz="0" iyz="0"/></inertial><collision><geometry><sphere radius="0.05"/>
    </geometry></collision></link>
  <joint name="caster_joint" type="fixed"><parent link="base_link"/><child link="caster"/>
    <origin xyz="-0.12 0 0"/></joint>
  %s %s
  <gazebo><plugin name="drive" filename="libgazebo_ros_diff_drive.so">
    <updateRate>50</updateRate><leftJoint>left_joint</leftJoint>
    <rightJoint>right_joint</rightJoint><wheelSeparation>0.24</wheelSeparation>
    <wheelDiameter>0.1</wheelDiameter><robotBaseFrame>base_link</robotBaseFrame>
    <commandTopic>cmd_vel</commandTopic><odometryTopic>odom</odometryTopic>
    <odometryFrame>odom</odometryFrame></plugin></gazebo>
  <gazebo reference="base_link">
    <sensor type="ray" name="lidar"><update_rate>10</update_rate><ray><scan><horizontal>
      <samples>360</samples><min_angle>-3.14159</min_angle><max_angle>3.14159</max_angle>
      </horizontal></scan><range><min>0.12</min><max>8</max></range></ray>
      <plugin name="laser" filename="libgazebo_ros_laser.so"><topicName>scan</topicName>
      <frameName>base_link</frameName></plugin></sensor>
  </gazebo>
  <gazebo><plugin name="imu" filename="libgazebo_ros_imu.so"><bodyName>base_link</bodyName>
    <topicName>imu</topicName><updateRate>100</updateRate></plugin></gazebo>
</robot>
""" % (wheel('left', 0.12), wheel('right', -0.12))

LISTENER = r"""
import json, sys, time
import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import Imu, LaserScan
from tf2_msgs.msg import TFMessage
from gazebo_msgs.srv import GetWorldProperties
rospy.init_node('rate_check', disable_signals=True)
stamps = {'scan': [], 'imu': [], 'odom': []}
tf = []
def rec(k):
    return lambda m: stamps[k].append(m.header.stamp.to_nsec())
def rec_tf(m):
    tf.append([(t.header.stamp.to_nsec(), t.header.frame_id, t.child_frame_id)
               for t in m.transforms])
subs = [rospy.Subscriber('/scan', LaserScan, rec('scan'), queue_size=10000),
        rospy.Subscriber('/imu', Imu, rec('imu'), queue_size=10000),
        rospy.Subscriber('/odom', Odometry, rec('odom'), queue_size=10000),
        rospy.Subscriber('/tf', TFMessage, rec_tf, queue_size=10000)]
pub = rospy.Publisher('/cmd_vel', Twist, queue_size=1, latch=True)
t = Twist(); t.linear.x = 0.1; t.angular.z = 0.3; pub.publish(t)
props = rospy.ServiceProxy('/gazebo/get_world_properties', GetWorldProperties)
rospy.wait_for_service('/gazebo/get_world_properties', timeout=60)
deadline = time.monotonic() + 120
while min(len(v) for v in stamps.values()) == 0 and time.monotonic() < deadline:
    time.sleep(0.05)
start = props().sim_time
while props().sim_time < start + float(sys.argv[1]) and time.monotonic() < deadline:
    time.sleep(0.05)
for s in subs:
    s.unregister()
time.sleep(0.5)
out = {k: sorted(v) for k, v in stamps.items()}
out['tf'] = tf
print(json.dumps(out))
"""


@pytest.mark.full
def test_every_sensor_message_arrives_at_its_rate_in_simulated_time(roscore, tmp_path):
    world = tmp_path / 'fast.world'
    world.write_text(WORLD)
    robot = tmp_path / 'bot.urdf'
    robot.write_text(ROBOT)
    env = roscore.env
    subprocess.run(['rosparam', 'set', '/use_sim_time', 'true'], env=env, check=True, timeout=30)
    node = Proc(['rosrun', 'ode_sim', 'sim_node', str(world)], env=env,
                log=str(tmp_path / 'sim.log'))
    try:
        spawn = subprocess.run(['rosrun', 'gazebo_ros', 'spawn_model', '-urdf', '-file',
                                str(robot), '-model', 'bot', '-z', '0.06'], env=env,
                               capture_output=True, text=True, timeout=120)
        assert spawn.returncode == 0, spawn.stdout + spawn.stderr + node.output()
        out = subprocess.run([sys.executable, '-c', LISTENER, '20'], env=env,
                             capture_output=True, text=True, timeout=300)
        assert out.returncode == 0, out.stderr[-3000:] + node.output()[-3000:]
    finally:
        node.stop()
    stamps = json.loads(out.stdout.strip().splitlines()[-1])
    for key, hz in (('scan', 10.0), ('imu', 100.0), ('odom', 50.0)):
        s = [t * 1e-9 for t in stamps[key]]
        assert len(s) > 5 * hz, (key, len(s), node.output()[-2000:])
        span = s[-1] - s[0]
        expected = int(round(span * hz)) + 1
        assert len(set(s)) == len(s), '%s: duplicate stamps' % key
        assert len(s) == expected, ('%s: %d of %d messages arrived between %.3f and %.3f s'
                                    % (key, len(s), expected, s[0], s[-1]))
        assert (len(s) - 1) / span == pytest.approx(hz, rel=0.01), key
    # /tf as a listener sees it: one message per step group, the odom -> base_link transform
    # with the odometry's own stamps and frames (as when each plugin call sent its own message)
    tf = stamps['tf']
    assert tf and all(len({t[0] for t in msg}) == 1 for msg in tf), tf[:5]
    odom_tf = sorted(t[0] for msg in tf for t in msg if t[1:] == ['odom', 'base_link'])
    assert odom_tf and {t[1:] == ['odom', 'base_link'] for msg in tf for t in msg} == {True}
    lo, hi = max(odom_tf[0], stamps['odom'][0]), min(odom_tf[-1], stamps['odom'][-1])
    assert [t for t in odom_tf if lo <= t <= hi] == [t for t in stamps['odom'] if lo <= t <= hi]
