#!/usr/bin/python3
"""rostest for the diploma's Diffbot: the diffbot node + spawner + a fake Arduino (test/
fake_arduino.py). A /diffbot_controller/cmd_vel command must give motor commands
trunc((v -/+ w*ws/2)/r) on motor_left_cmd / motor_right_cmd (Int32: the Diffbot's write()
truncates), odometry must follow the measured wheel speeds (sim time), and the start / stop
services must turn the joint states to NaN and back."""
import math
import threading
import time
import unittest

import rospy
import rostest
from controller_manager_msgs.srv import ListControllers
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import JointState
from std_msgs.msg import Int32
from std_srvs.srv import Empty

WHEEL_SEPARATION = 0.182
WHEEL_RADIUS = 0.0325
WAIT = 60.0  # wall-clock seconds: generous limits for waits only, never a pass/fail threshold


def wheel_commands(v, w):
    return (int((v - w * WHEEL_SEPARATION / 2) / WHEEL_RADIUS),
            int((v + w * WHEEL_SEPARATION / 2) / WHEEL_RADIUS))


class DiffbotHwTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("check_diffbot_hw")
        cls.lock = threading.Lock()
        cls.motor = {"left": None, "right": None}
        cls.odom = None
        cls.joints = None
        cls.subs = [
            rospy.Subscriber("/motor_left_cmd", Int32, cls.on_motor, callback_args="left"),
            rospy.Subscriber("/motor_right_cmd", Int32, cls.on_motor, callback_args="right"),
            rospy.Subscriber("/diffbot_controller/odom", Odometry, cls.on_odom),
            rospy.Subscriber("/joint_states", JointState, cls.on_joints),
        ]
        cls.cmd_pub = rospy.Publisher("/diffbot_controller/cmd_vel", Twist, queue_size=1)
        cls.cmd = None
        cls.cmd_timer = threading.Thread(target=cls.publish_cmd, daemon=True)
        cls.cmd_timer.start()

    @classmethod
    def on_motor(cls, msg, side):
        with cls.lock:
            cls.motor[side] = msg.data

    @classmethod
    def on_odom(cls, msg):
        with cls.lock:
            cls.odom = msg

    @classmethod
    def on_joints(cls, msg):
        with cls.lock:
            cls.joints = msg

    @classmethod
    def publish_cmd(cls):
        while not rospy.is_shutdown():
            if cls.cmd is not None:
                cls.cmd_pub.publish(cls.cmd)
            rospy.rostime.wallsleep(0.05)

    def wait_for(self, cond, what, timeout=WAIT):
        t_end = time.monotonic() + timeout
        while time.monotonic() < t_end and not rospy.is_shutdown():
            with self.lock:
                ok = cond()
            if ok:
                return
            rospy.rostime.wallsleep(0.05)
        self.fail("timed out after %.0f s waiting for %s" % (timeout, what))

    def wait_sim(self, seconds):
        self.wait_for(lambda: rospy.Time.now().to_sec() > 0, "/clock from the diffbot")
        t_end = rospy.Time.now().to_sec() + seconds
        self.wait_for(lambda: rospy.Time.now().to_sec() >= t_end, "%.1f s of sim time" % seconds)

    def wait_running(self):
        rospy.wait_for_service("/controller_manager/list_controllers", timeout=WAIT)
        srv = rospy.ServiceProxy("/controller_manager/list_controllers", ListControllers)

        def running():
            states = {c.name: c.state for c in srv().controller}
            return states.get("diffbot_controller") == "running" and \
                states.get("joint_state_controller") == "running"
        self.wait_for(running, "diffbot_controller and joint_state_controller running")

    def drive(self, v, w):
        t = Twist()
        t.linear.x, t.angular.z = v, w
        type(self).cmd = t

    def test_a_motor_commands_and_odometry(self):
        self.wait_running()
        for v, w in ((0.2, 0.0), (0.2, 1.0), (0.0, -2.0)):
            left, right = wheel_commands(v, w)
            self.drive(v, w)
            self.wait_for(lambda: (self.motor["left"], self.motor["right"]) == (left, right),
                          "motor_left_cmd/motor_right_cmd = %d/%d for v=%.2f w=%.2f (last seen %s)"
                          % (left, right, v, w, self.motor))
            self.wait_sim(0.5)  # the fake Arduino's wheels settle
            with self.lock:
                o0 = self.odom
            self.assertIsNotNone(o0, "no odometry on /diffbot_controller/odom")
            self.wait_sim(2.0)
            with self.lock:
                o1 = self.odom
            dt = (o1.header.stamp - o0.header.stamp).to_sec()
            v_exp = (left + right) / 2.0 * WHEEL_RADIUS
            w_exp = (right - left) * WHEEL_RADIUS / WHEEL_SEPARATION
            self.assertAlmostEqual(o1.twist.twist.linear.x, v_exp, delta=0.01,
                                   msg="odometry linear speed for v=%.2f w=%.2f" % (v, w))
            self.assertAlmostEqual(o1.twist.twist.angular.z, w_exp, delta=0.03,
                                   msg="odometry angular speed for v=%.2f w=%.2f" % (v, w))
            p0, p1 = o0.pose.pose.position, o1.pose.pose.position
            dist = math.hypot(p1.x - p0.x, p1.y - p0.y)
            if v > 0 and w == 0:
                self.assertAlmostEqual(dist, v_exp * dt, delta=0.05 * v_exp * dt + 0.01,
                                       msg="odometry distance over %.2f s of sim time" % dt)
            if v == 0:
                self.assertLess(dist, 0.01, "odometry moved while turning in place")
        self.drive(0.0, 0.0)
        self.wait_for(lambda: (self.motor["left"], self.motor["right"]) == (0, 0),
                      "motor commands 0/0 after a zero cmd_vel (last seen %s)" % self.motor)

    def test_b_start_stop(self):
        self.wait_running()
        rospy.wait_for_service("/stop", timeout=WAIT)
        rospy.ServiceProxy("/stop", Empty)()
        self.wait_for(lambda: self.joints is not None and all(math.isnan(x) for x in self.joints.velocity),
                      "NaN joint velocities on /joint_states after /stop")
        self.wait_sim(0.5)
        with self.lock:
            o = self.odom
        self.assertFalse(math.isnan(o.pose.pose.position.x) or math.isnan(o.twist.twist.linear.x),
                         "odometry became NaN after /stop")
        rospy.ServiceProxy("/start", Empty)()
        self.wait_for(lambda: not any(math.isnan(x) for x in self.joints.velocity),
                      "finite joint velocities on /joint_states after /start")
        self.wait_sim(0.5)
        with self.lock:
            o = self.odom
        self.assertFalse(math.isnan(o.pose.pose.position.x), "odometry became NaN after /start")


if __name__ == "__main__":
    rostest.rosrun("space_scanner_hw", "check_diffbot_hw", DiffbotHwTest)
