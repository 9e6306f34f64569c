#!/usr/bin/env python3
"""drive.test: the space scanner through ros_control. diffbot_controller gets 0.3 m/s on
/diffbot_controller/cmd_vel for 10 s of sim time: the robot covers 0.3 m/s times the time it
drove ± 3 % by ground truth (/gazebo/get_model_state) and diffbot_controller's odometry agrees
within 2 %. The time it drove is taken from the odometry's stamps (from the first message
above half the speed to the first one below it after the stop command), not from when this
node happened to publish: on a loaded machine the simulation may run ahead of this node, so
its commands start and stop at sim times it cannot choose.
Params (for the skid-steer comparison): ~cmd_vel (/diffbot_controller/cmd_vel), ~odom
(/diffbot_controller/odom), ~controllers (true: wait for the controllers)."""
import math
import threading
import time
import unittest

import rospy
import rostest
from controller_manager_msgs.srv import ListControllers
from gazebo_msgs.srv import GetModelState
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry

WALL_TIMEOUT = 150.0
SPEED = 0.3          # m/s
DURATION = 10.0      # s of sim time
DISTANCE_TOLERANCE = 0.03
ODOM_TOLERANCE = 0.02


class DriveTest(unittest.TestCase):
    def setUp(self):
        self.lock = threading.Lock()
        self.odom = None
        self.track = []    # (stamp, forward speed) of every odometry message
        self.cmd_topic = rospy.get_param('~cmd_vel', '/diffbot_controller/cmd_vel')
        self.controllers = rospy.get_param('~controllers', True)
        rospy.Subscriber(rospy.get_param('~odom', '/diffbot_controller/odom'), Odometry, self.on_odom,
                         queue_size=10)

    def on_odom(self, msg):
        with self.lock:
            self.odom = msg
            self.track.append((msg.header.stamp.to_sec(), msg.twist.twist.linear.x))

    def wait(self, cond, what):
        end = time.monotonic() + WALL_TIMEOUT
        while not cond():
            if rospy.is_shutdown() or time.monotonic() > end:
                self.fail('timed out (%.0f s wall) waiting for %s' % (WALL_TIMEOUT, what))
            time.sleep(0.05)

    def sim_sleep(self, seconds, what):
        t_end = rospy.Time.now().to_sec() + seconds
        self.wait(lambda: rospy.Time.now().to_sec() >= t_end, what)

    def odom_xy(self):
        with self.lock:
            p = self.odom.pose.pose.position
        return p.x, p.y

    def test_drive_3m(self):
        rospy.wait_for_service('/gazebo/get_model_state', WALL_TIMEOUT)
        get = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)
        if self.controllers:
            rospy.wait_for_service('/controller_manager/list_controllers', WALL_TIMEOUT)
            lc = rospy.ServiceProxy('/controller_manager/list_controllers', ListControllers)

            def running():
                states = {c.name: c.state for c in lc().controller}
                return (states.get('diffbot_controller') == 'running'
                        and states.get('joint_state_controller') == 'running')
            self.wait(running, 'diffbot_controller and joint_state_controller running (spawner)')
        self.wait(lambda: get(model_name='robot').success, "the model 'robot'")
        self.wait(lambda: get(model_name='robot').pose.position.z < 0.05, 'the robot landing on its wheels')
        self.sim_sleep(1.0, 'the robot settling')
        self.wait(lambda: self.odom is not None, '/diffbot_controller/odom')
        p0 = get(model_name='robot').pose.position
        o0 = self.odom_xy()
        pub = rospy.Publisher(self.cmd_topic, Twist, queue_size=1)
        self.wait(lambda: pub.get_num_connections() > 0, 'a subscriber of %s' % self.cmd_topic)
        cmd = Twist()
        cmd.linear.x = SPEED
        t0 = rospy.Time.now().to_sec()
        end = time.monotonic() + WALL_TIMEOUT
        while rospy.Time.now().to_sec() < t0 + DURATION:
            self.assertLess(time.monotonic(), end, 'sim time stalled while driving')
            pub.publish(cmd)
            rospy.sleep(0.02)       # sim time: 50 Hz of commands
        pub.publish(Twist())
        self.sim_sleep(1.0, 'the robot stopping')
        p1 = get(model_name='robot').pose.position
        o1 = self.odom_xy()
        truth = math.hypot(p1.x - p0.x, p1.y - p0.y)
        odom = math.hypot(o1[0] - o0[0], o1[1] - o0[1])
        with self.lock:
            track = [(t, v) for t, v in self.track if t >= t0 - 0.5]
        moving = [t for t, v in track if v > SPEED / 2]
        self.assertTrue(moving, 'the odometry never showed the robot moving at %.2f m/s' % SPEED)
        stopped = [t for t, v in track if t > moving[0] and v < SPEED / 2]
        self.assertTrue(stopped, 'the odometry never showed the robot stopping')
        drove = stopped[0] - moving[0]
        want = SPEED * drove
        rospy.loginfo('drive: ground truth %.4f m, odometry %.4f m, want %.2f m/s x %.3f s = %.4f m',
                      truth, odom, SPEED, drove, want)
        self.assertAlmostEqual(drove, DURATION, delta=0.5 * DURATION,
                               msg='the robot drove %.2f s of sim time for %.0f s of commands' % (drove, DURATION))
        self.assertAlmostEqual(truth, want, delta=DISTANCE_TOLERANCE * want,
                               msg='ground truth distance %.4f m, want %.2f m/s x %.3f s = %.4f m ± 3 %%' % (
                                   truth, SPEED, drove, want))
        self.assertAlmostEqual(odom, truth, delta=ODOM_TOLERANCE * truth,
                               msg='odometry %.4f m vs ground truth %.4f m (2 %%)' % (odom, truth))


if __name__ == '__main__':
    rospy.init_node('drive_check')
    rostest.rosrun('space_scanner_simulation', 'drive_check', DriveTest)
