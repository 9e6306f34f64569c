#!/usr/bin/env python3
"""DiffDriveController on the diffbot (sim time), driven like a user: spawner + YAML, Twist on
/diffbot_controller/cmd_vel, odometry on /diffbot_controller/odom and /tf.

One script, several scenarios (the argument from the .test file): basic, timeout, limits,
options, fail. Distances are checked against v*t over sim time, with named tolerances."""
import math
import sys
import threading
import time
import unittest

import rospy
import rostest
from course_runtime.geometry import yaw_of
from course_testing.rosout import RosoutProbe, rosout_connected
from control_msgs.msg import JointTrajectoryControllerState
from controller_manager_msgs.srv import ListControllers, LoadController, SwitchController
from geometry_msgs.msg import Twist, TwistStamped
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Log
from sensor_msgs.msg import JointState
from std_srvs.srv import Empty
from tf2_msgs.msg import TFMessage

POSITION_TOLERANCE = 0.01     # [m]
ORIENTATION_TOLERANCE = 0.01  # [rad]
VELOCITY_TOLERANCE = 0.02     # [m/s], [rad/s]
WALL_TIMEOUT = 60.0           # bound on every wait [wall s]
WHEEL_RADIUS = 0.11           # test/diffbot.urdf
WHEEL_SEPARATION = 1.0
CM = '/controller_manager/'
MODE = 'basic'


class DiffDriveTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('test_diff_drive')
        cls.lock = threading.Lock()
        cls.odom = []
        cls.js = None
        cls.tf = None
        cls.cmd_out = None
        cls.wheel_state = None
        cls.logs = []
        rospy.Subscriber('/diffbot_controller/odom', Odometry, cls._odom, queue_size=1000)
        rospy.Subscriber('/joint_states', JointState, cls._set, 'js')
        rospy.Subscriber('/tf', TFMessage, cls._tf)
        rospy.Subscriber('/diffbot_controller/cmd_vel_out', TwistStamped, cls._set, 'cmd_out')
        rospy.Subscriber('/diffbot_controller/wheel_joint_controller_state', JointTrajectoryControllerState,
                         cls._set, 'wheel_state')
        cls.rosout = rospy.Subscriber('/rosout', Log, lambda m: cls.logs.append(m.msg), queue_size=1000)
        cls.cmd_pub = rospy.Publisher('/diffbot_controller/cmd_vel', Twist, queue_size=10)
        rospy.wait_for_service(CM + 'list_controllers', WALL_TIMEOUT)
        cls.list = rospy.ServiceProxy(CM + 'list_controllers', ListControllers)
        cls.load = rospy.ServiceProxy(CM + 'load_controller', LoadController)
        cls.switch = rospy.ServiceProxy(CM + 'switch_controller', SwitchController)
        cls.wait_for('/rosout of the diffbot', lambda: rosout_connected(cls.rosout, '/diffbot'))
        # lines of /diffbot really arrive: its controller manager logs one for a controller
        # without a type
        cls.wait_for('a line of /diffbot on /rosout',
                     RosoutProbe(cls.logs, "'rosout_probe'", lambda: cls.load('rosout_probe')))
        if MODE != 'fail':
            cls.wait_for('diffbot_controller running',
                         lambda: cls.state_of('diffbot_controller') == 'running')
            cls.wait_for('odometry', lambda: len(cls.odom) > 0)
            cls.wait_for('cmd_vel subscriber', lambda: cls.cmd_pub.get_num_connections() > 0)

    @classmethod
    def _odom(cls, msg):
        with cls.lock:
            cls.odom.append(msg)

    @classmethod
    def _set(cls, msg, attr):
        with cls.lock:
            setattr(cls, attr, msg)

    @classmethod
    def _tf(cls, msg):
        for t in msg.transforms:
            if t.child_frame_id in ('base_link', 'base_footprint'):
                with cls.lock:
                    cls.tf = t

    @classmethod
    def state_of(cls, name):
        return {c.name: c.state for c in cls.list().controller}.get(name)

    @classmethod
    def wait_for(cls, what, condition):
        start = time.time()
        while not rospy.is_shutdown() and not condition():
            if time.time() - start > WALL_TIMEOUT:
                raise AssertionError('%s: not reached within %.0f s of wall time' % (what, WALL_TIMEOUT))
            time.sleep(0.005)

    def last_odom(self):
        with self.lock:
            return self.odom[-1]

    def wait_sim(self, seconds):
        end = rospy.Time.now() + rospy.Duration(seconds)
        self.wait_for('%.2f s of sim time' % seconds, lambda: rospy.Time.now() >= end)

    def drive(self, lin, ang, seconds):
        """Publish (lin, ang) every 50 ms of sim time for `seconds` of sim time."""
        end = rospy.Time.now() + rospy.Duration(seconds)
        twist = Twist()
        twist.linear.x = lin
        twist.angular.z = ang
        last = rospy.Time.now()
        while rospy.Time.now() < end:
            last = rospy.Time.now()
            self.cmd_pub.publish(twist)
            self.wait_sim(0.05)
        return last   # sim time of the last command sent

    def stop_and_settle(self):
        self.drive(0.0, 0.0, 0.5)

    def wheel_velocities(self):
        with self.lock:
            js = self.js
        return js.velocity[js.name.index('wheel_0_joint')], js.velocity[js.name.index('wheel_1_joint')]

    # --- basic --------------------------------------------------------------------------------
    def test_basic_forward(self):
        self.stop_and_settle()
        self.drive(1.0, 0.0, 1.0)                 # reach steady state
        start = self.last_odom()
        self.drive(1.0, 0.0, 3.0)
        end = self.last_odom()
        dt = (end.header.stamp - start.header.stamp).to_sec()
        self.assertGreater(dt, 2.5)
        self.assertAlmostEqual(end.pose.pose.position.x - start.pose.pose.position.x, 1.0 * dt,
                               delta=POSITION_TOLERANCE)
        self.assertAlmostEqual(end.pose.pose.position.y - start.pose.pose.position.y, 0.0,
                               delta=POSITION_TOLERANCE)
        self.assertAlmostEqual(end.twist.twist.linear.x, 1.0, delta=VELOCITY_TOLERANCE)
        # wheel speeds from the URDF's radius: v / r on both wheels
        left, right = self.wheel_velocities()
        self.assertAlmostEqual(left, 1.0 / WHEEL_RADIUS, delta=1e-6)
        self.assertAlmostEqual(right, 1.0 / WHEEL_RADIUS, delta=1e-6)
        self.assertEqual(end.header.frame_id, 'odom')
        self.assertEqual(end.child_frame_id, 'base_link')
        self.assertEqual(end.pose.covariance[0], 0.001)
        self.assertEqual(end.pose.covariance[35], 1000.0)
        self.stop_and_settle()

    def test_basic_rotation(self):
        self.stop_and_settle()
        self.drive(0.0, 0.5, 1.0)
        start = self.last_odom()
        self.drive(0.0, 0.5, 2.0)
        end = self.last_odom()
        dt = (end.header.stamp - start.header.stamp).to_sec()
        turned = yaw_of(end.pose.pose.orientation) - yaw_of(start.pose.pose.orientation)
        turned = math.atan2(math.sin(turned), math.cos(turned))
        self.assertAlmostEqual(turned, 0.5 * dt, delta=ORIENTATION_TOLERANCE)
        self.assertAlmostEqual(end.pose.pose.position.x, start.pose.pose.position.x, delta=POSITION_TOLERANCE)
        self.assertAlmostEqual(end.twist.twist.angular.z, 0.5, delta=VELOCITY_TOLERANCE)
        # wheel speeds from the URDF's separation: -+ w * s / 2 / r
        left, right = self.wheel_velocities()
        self.assertAlmostEqual(left, -0.5 * WHEEL_SEPARATION / 2 / WHEEL_RADIUS, delta=1e-6)
        self.assertAlmostEqual(right, 0.5 * WHEEL_SEPARATION / 2 / WHEEL_RADIUS, delta=1e-6)
        self.stop_and_settle()

    def test_basic_tf_matches_odom(self):
        self.wait_for('odom -> base_link on /tf', lambda: self.tf is not None)
        self.stop_and_settle()
        with self.lock:
            tf = self.tf
        odom = self.last_odom()
        self.assertEqual(tf.header.frame_id, 'odom')
        self.assertAlmostEqual(tf.transform.translation.x, odom.pose.pose.position.x, delta=1e-9)

    def test_basic_nan_is_ignored(self):
        self.stop_and_settle()
        self.drive(float('nan'), 0.0, 0.5)
        self.wait_for('NaN warning', lambda: any('Received NaN in velocity command. Ignoring.' in m
                                                 for m in list(self.logs)))
        odom = self.last_odom()
        self.assertFalse(math.isnan(odom.pose.pose.position.x))
        self.assertAlmostEqual(odom.twist.twist.linear.x, 0.0, delta=VELOCITY_TOLERANCE)

    def test_basic_z_hardware_stop_gives_no_nan(self):
        stop = rospy.ServiceProxy('/stop', Empty)
        start = rospy.ServiceProxy('/start', Empty)
        before = self.last_odom()
        stop()
        self.drive(0.5, 0.0, 0.5)
        start()
        self.drive(0.0, 0.0, 0.5)
        after = self.last_odom()
        for value in (after.pose.pose.position.x, after.pose.pose.position.y, after.twist.twist.linear.x):
            self.assertFalse(math.isnan(value))
        self.assertAlmostEqual(after.pose.pose.position.x, before.pose.pose.position.x, delta=POSITION_TOLERANCE)
        # and it drives on after the restart
        self.drive(1.0, 0.0, 1.0)
        start = self.last_odom()
        self.drive(1.0, 0.0, 1.0)
        end = self.last_odom()
        dt = (end.header.stamp - start.header.stamp).to_sec()
        travelled = math.hypot(end.pose.pose.position.x - start.pose.pose.position.x,
                               end.pose.pose.position.y - start.pose.pose.position.y)   # heading is not 0 here
        self.assertAlmostEqual(travelled, 1.0 * dt, delta=POSITION_TOLERANCE)
        self.stop_and_settle()

    def test_basic_zz_not_running_refuses_commands(self):
        self.assertTrue(self.switch([], ['diffbot_controller'], 2, False, 0.0).ok)
        self.cmd_pub.publish(Twist())
        self.wait_for('not-running error', lambda: any(
            "Can't accept new commands. Controller is not running." in m for m in list(self.logs)))
        self.assertTrue(self.switch(['diffbot_controller'], [], 2, False, 0.0).ok)

    # --- timeout ------------------------------------------------------------------------------
    def test_timeout_brakes(self):
        last_cmd = self.drive(1.0, 0.0, 1.0)
        self.assertAlmostEqual(self.last_odom().twist.twist.linear.x, 1.0, delta=VELOCITY_TOLERANCE)
        self.wait_sim(2.0)   # no more commands: cmd_vel_timeout (0.5 s) later the wheels stop
        self.assertEqual(self.wheel_velocities(), (0.0, 0.0))
        odom = self.last_odom()
        self.assertAlmostEqual(odom.twist.twist.linear.x, 0.0, delta=VELOCITY_TOLERANCE)
        with self.lock:
            at_cmd = [m for m in self.odom if m.header.stamp >= last_cmd][0]
        # from the last command on it went on for the timeout only: 0.5 s at 1 m/s (plus the
        # command's delivery delay, which the controller stamps on receipt)
        travelled = odom.pose.pose.position.x - at_cmd.pose.pose.position.x
        self.assertGreater(travelled, 0.5 - 0.03)
        self.assertLess(travelled, 0.5 + 0.15)

    # --- limits -------------------------------------------------------------------------------
    def test_limits_velocity_and_acceleration(self):
        t0 = rospy.Time.now()
        self.drive(10.0, 0.0, 2.5)
        # max_acceleration 1 m/s^2, max_velocity 1 m/s: v(t) <= min(1 * (t - t0), 1) all along
        with self.lock:
            ramp = [m for m in self.odom if m.header.stamp >= t0]
        self.assertGreater(len(ramp), 50)
        for m in ramp:
            bound = min((m.header.stamp - t0).to_sec(), 1.0)
            self.assertLessEqual(m.twist.twist.linear.x, bound + VELOCITY_TOLERANCE,
                                 'faster than the limits allow at t0 + %.2f s' % (m.header.stamp - t0).to_sec())
        self.assertAlmostEqual(self.last_odom().twist.twist.linear.x, 1.0, delta=VELOCITY_TOLERANCE)
        self.drive(-10.0, 0.0, 5.0)   # min_velocity -0.5 m/s
        self.assertAlmostEqual(self.last_odom().twist.twist.linear.x, -0.5, delta=VELOCITY_TOLERANCE)
        self.drive(0.0, 10.0, 3.0)    # angular max_velocity 2 rad/s
        self.assertAlmostEqual(self.last_odom().twist.twist.angular.z, 2.0, delta=VELOCITY_TOLERANCE)
        self.drive(0.0, 0.0, 3.0)

    # --- options ------------------------------------------------------------------------------
    def test_options_frames_cmd_out_and_wheel_state(self):
        self.drive(0.4, 0.2, 1.0)
        odom = self.last_odom()
        self.assertEqual(odom.header.frame_id, 'odom_test')
        self.assertEqual(odom.child_frame_id, 'base_footprint')
        self.wait_for('cmd_vel_out', lambda: self.cmd_out is not None)
        self.assertAlmostEqual(self.cmd_out.twist.linear.x, 0.4)
        self.assertAlmostEqual(self.cmd_out.twist.angular.z, 0.2)
        self.wait_for('wheel_joint_controller_state', lambda: self.wheel_state is not None)
        self.assertEqual(self.wheel_state.joint_names, ['wheel_0_joint', 'wheel_1_joint'])
        self.assertAlmostEqual(self.wheel_state.desired.velocities[0], (0.4 - 0.2 * 0.5) / WHEEL_RADIUS)
        self.drive(0.0, 0.0, 0.3)

    def test_options_second_publisher_brakes(self):
        other = rospy.Publisher('/diffbot_controller/cmd_vel', Twist, queue_size=1)
        # a second node is needed for a second publisher connection: use rostopic
        import subprocess
        proc = subprocess.Popen(['rostopic', 'pub', '-r', '20', '/diffbot_controller/cmd_vel',
                                 'geometry_msgs/Twist', '{linear: {x: 0.3}}'],
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        try:
            self.wait_for('the brake error', lambda: any(
                'publishers. Only 1 publisher is allowed. Going to brake.' in m for m in list(self.logs)))
            self.drive(0.5, 0.0, 0.5)
            self.assertEqual(self.wheel_velocities(), (0.0, 0.0))
        finally:
            proc.terminate()
            proc.wait(timeout=30)
            other.unregister()

    def test_options_z_dynamic_reconfigure(self):
        import dynamic_reconfigure.client
        client = dynamic_reconfigure.client.Client('/diffbot_controller', timeout=WALL_TIMEOUT)
        client.update_configuration({'left_wheel_radius_multiplier': 1.5, 'right_wheel_radius_multiplier': 1.5,
                                     'publish_rate': 10.0})
        self.drive(0.33, 0.0, 1.0)
        left, right = self.wheel_velocities()
        self.assertAlmostEqual(left, 0.33 / (1.5 * WHEEL_RADIUS), delta=1e-6)
        start = rospy.Time.now() + rospy.Duration(0.1)
        end = start + rospy.Duration(2.0)
        self.drive(0.33, 0.0, 2.5)
        with self.lock:
            stamps = [m.header.stamp for m in self.odom if start <= m.header.stamp < end]
        self.assertIn(len(stamps), range(18, 22))   # 10 Hz over 2 s of sim time
        client.update_configuration({'left_wheel_radius_multiplier': 1.0, 'right_wheel_radius_multiplier': 1.0,
                                     'publish_rate': 50.0})
        self.drive(0.0, 0.0, 0.3)

    # --- multiwheel ---------------------------------------------------------------------------
    def test_multiwheel_forward_and_turn(self):
        self.drive(0.5, 0.2, 1.0)
        start = self.last_odom()
        self.drive(0.5, 0.2, 2.0)
        end = self.last_odom()
        dt = (end.header.stamp - start.header.stamp).to_sec()
        turned = yaw_of(end.pose.pose.orientation) - yaw_of(start.pose.pose.orientation)
        self.assertAlmostEqual(turned, 0.2 * dt, delta=ORIENTATION_TOLERANCE)
        chord = math.hypot(end.pose.pose.position.x - start.pose.pose.position.x,
                           end.pose.pose.position.y - start.pose.pose.position.y)
        # arc of radius v / w: chord = 2 (v / w) sin(w dt / 2)
        self.assertAlmostEqual(chord, 2 * (0.5 / 0.2) * math.sin(0.2 * dt / 2), delta=POSITION_TOLERANCE)
        with self.lock:
            js = self.js
        vel = dict(zip(js.name, js.velocity))
        self.assertEqual(vel['wheel_0_joint'], vel['wheel_2_joint'])
        self.assertEqual(vel['wheel_1_joint'], vel['wheel_3_joint'])
        self.assertAlmostEqual(vel['wheel_0_joint'], (0.5 - 0.2 * WHEEL_SEPARATION / 2) / WHEEL_RADIUS, delta=1e-6)
        self.drive(0.0, 0.0, 0.3)

    # --- fail ---------------------------------------------------------------------------------
    def _load_fails_with(self, name, message):
        self.assertFalse(self.load(name).ok, '%s came up although misconfigured' % name)
        self.wait_for('log "%s"' % message, lambda: any(message in m for m in list(self.logs)))
        self.assertIsNone(self.state_of(name))

    def test_fail_wrong_wheel_name(self):
        self._load_fails_with('wrong_wheel_controller',
                              'this_joint_does_not_exist couldn\'t be retrieved from model description')

    def test_fail_unequal_wheels(self):
        self._load_fails_with('unequal_wheels_controller', '#left wheels (2) != #right wheels (1).')

    def test_fail_missing_wheel(self):
        self._load_fails_with('no_wheel_controller', "Couldn't retrieve wheel param 'left_wheel'.")

    def test_fail_wheel_not_a_string(self):
        self._load_fails_with('bad_wheel_type_controller',
                              "Wheel param 'left_wheel' is neither a list of strings nor a string.")

    def test_fail_missing_covariance(self):
        self._load_fails_with('no_covariance_controller', 'pose_covariance_diagonal')


if __name__ == '__main__':
    args = rospy.myargv(sys.argv)[1:]
    MODE = args[0] if args else 'basic'
    # run only this scenario's tests (test_<mode>_...)
    for attr in list(vars(DiffDriveTest)):
        if attr.startswith('test_') and not attr.startswith('test_%s_' % MODE):
            delattr(DiffDriveTest, attr)
    rostest.rosrun('diff_drive_controller', 'diff_drive_' + MODE, DiffDriveTest, sys.argv)
