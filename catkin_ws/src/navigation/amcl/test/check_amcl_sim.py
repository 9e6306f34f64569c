#!/usr/bin/env python3
"""amcl_office.test: publishes the office map latched on /map, drives the space scanner on a
slow arc around its spawn point and checks amcl against the simulator's ground truth
(/gazebo/get_model_state): converged within CONVERGE_S of sim time, then tracking, plus the
interfaces (particlecloud, map -> odom TF, request_nomotion_update)."""
import math
import os
import threading
import time
import unittest

import numpy as np
import rospy
import rostest
import tf2_ros
import yaml
from gazebo_msgs.srv import GetModelState
from geometry_msgs.msg import PoseArray, PoseWithCovarianceStamped, Twist
from nav_msgs.msg import OccupancyGrid
from std_srvs.srv import Empty

from course_runtime.geometry import yaw_of

WALL_TIMEOUT = 150.0
CONVERGE_S = 4.0          # s of sim time driving
TOL_XY, TOL_YAW = 0.10, 0.10      # converged: amcl's TF against the ground truth
# while driving, TF and ground truth are read at slightly different sim times (a service
# round trip while the simulator runs faster than real time): only a sanity bound
DRIVE_XY, DRIVE_YAW = 0.20, 0.20
STATIC_XY, STATIC_YAW = 0.08, 0.08  # after stopping: an exact comparison
NOMOTION_UPDATES = 15   # no-motion updates allowed to recover from a wrong initialpose
RECOVER_XY, RECOVER_YAW = 0.25, 0.15  # at rest after them: most of the 0.5 m / 0.35 rad gone


def load_map(yaml_path):
    """map_server's trinary interpretation of a P5 PGM (the test needs no map_server)."""
    with open(yaml_path) as f:
        meta = yaml.safe_load(f)
    with open(os.path.join(os.path.dirname(yaml_path), meta['image']), 'rb') as f:
        raw = f.read()
    fields, pos = [], 0
    while len(fields) < 4:
        while raw[pos:pos + 1].isspace():
            pos += 1
        if raw[pos:pos + 1] == b'#':
            pos = raw.index(b'\n', pos) + 1
            continue
        end = pos
        while not raw[end:end + 1].isspace():
            end += 1
        fields.append(raw[pos:end])
        pos = end
    w, h = int(fields[1]), int(fields[2])
    img = np.frombuffer(raw[pos + 1:pos + 1 + w * h], dtype=np.uint8).reshape(h, w)[::-1]
    p = (255 - img.astype(float)) / 255.0
    data = np.full(img.shape, -1, dtype=np.int8)
    data[p > meta['occupied_thresh']] = 100
    data[p < meta['free_thresh']] = 0
    msg = OccupancyGrid()
    msg.header.frame_id = 'map'
    msg.info.resolution = meta['resolution']
    msg.info.width, msg.info.height = w, h
    msg.info.origin.position.x, msg.info.origin.position.y = meta['origin'][0], meta['origin'][1]
    msg.info.origin.orientation.w = 1.0
    msg.data = data.ravel().tolist()
    return msg


class AmclOfficeTest(unittest.TestCase):
    def setUp(self):
        self.lock = threading.Lock()
        self.pose = None
        self.cloud = None
        rospy.Subscriber('/amcl_pose', PoseWithCovarianceStamped, self.on_pose)
        rospy.Subscriber('/particlecloud', PoseArray, self.on_cloud)
        self.tf_buffer = tf2_ros.Buffer()
        self.tf_listener = tf2_ros.TransformListener(self.tf_buffer)

    def on_pose(self, msg):
        with self.lock:
            self.pose = msg

    def on_cloud(self, msg):
        with self.lock:
            self.cloud = msg

    def wait(self, cond, what):
        end = time.monotonic() + WALL_TIMEOUT
        while not cond():
            if rospy.is_shutdown() or time.monotonic() > end:
                self.fail('timed out (%.0f s wall) waiting for %s' % (WALL_TIMEOUT, what))
            time.sleep(0.05)

    def error(self):
        """amcl's map -> base_footprint (TF) against the ground truth: (metres, radians)."""
        truth = self.get(model_name='robot').pose
        t = self.tf_buffer.lookup_transform('map', 'base_footprint', rospy.Time(0)).transform
        dxy = math.hypot(t.translation.x - truth.position.x, t.translation.y - truth.position.y)
        dyaw = abs((yaw_of(t.rotation) - yaw_of(truth.orientation) + math.pi) % (2 * math.pi) - math.pi)
        return dxy, dyaw

    def drive(self, turn):
        """Drives a slow arc for CONVERGE_S + 2 s of sim time, then stops: (the sim time at which
        amcl came within TOL_XY / TOL_YAW of the truth and stayed there up to CONVERGE_S or
        None, the errors after CONVERGE_S, the last error)."""
        cmd = Twist()
        cmd.linear.x, cmd.angular.z = 0.15, turn
        t0 = rospy.Time.now().to_sec()
        end = time.monotonic() + WALL_TIMEOUT
        converged_at = None
        errors = []
        while rospy.Time.now().to_sec() < t0 + CONVERGE_S + 2.0:
            self.assertLess(time.monotonic(), end, 'sim time stalled while driving')
            self.cmd_pub.publish(cmd)
            rospy.sleep(0.1)
            dxy, dyaw = self.error()
            now = rospy.Time.now().to_sec() - t0
            if dxy < TOL_XY and dyaw < TOL_YAW:
                if converged_at is None:
                    converged_at = now
            else:
                converged_at = None if now < CONVERGE_S else converged_at
            if now > CONVERGE_S:
                errors.append((dxy, dyaw))
        self.cmd_pub.publish(Twist())
        return converged_at, errors, (dxy, dyaw)

    def nomotion_updates(self, nomotion, at_least):
        """request_nomotion_update until at least `at_least` updates are published and the error
        is within STATIC_*, NOMOTION_UPDATES at most: (updates, error m, error rad)."""
        for n in range(1, NOMOTION_UPDATES + 1):
            stamp = self.pose.header.stamp
            nomotion()
            self.wait(lambda: self.pose.header.stamp > stamp, 'an /amcl_pose after request_nomotion_update')
            dxy, dyaw = self.error()
            if n >= at_least and dxy < STATIC_XY and dyaw < STATIC_YAW:
                break
        return n, dxy, dyaw

    @staticmethod
    def initial_pose_off(truth):
        """An /initialpose 0.5 m / 20 deg off the pose `truth`."""
        init = PoseWithCovarianceStamped()
        init.header.frame_id = 'map'
        init.header.stamp = rospy.Time.now()
        yaw = yaw_of(truth.orientation) + math.radians(20)
        init.pose.pose.position.x = truth.position.x + 0.35
        init.pose.pose.position.y = truth.position.y - 0.35
        init.pose.pose.orientation.z, init.pose.pose.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
        init.pose.covariance[0] = init.pose.covariance[7] = 0.25
        init.pose.covariance[35] = 0.07
        return init

    def test_converges_and_tracks(self):
        map_pub = rospy.Publisher('/map', OccupancyGrid, queue_size=1, latch=True)
        map_pub.publish(load_map(rospy.get_param('~map_file')))
        rospy.wait_for_service('/gazebo/get_model_state', WALL_TIMEOUT)
        self.get = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)
        self.wait(lambda: self.get(model_name='robot').success, "the model 'robot'")
        self.wait(lambda: self.get(model_name='robot').pose.position.z < 0.05, 'the robot landing on its wheels')
        self.wait(lambda: self.pose is not None, 'a first /amcl_pose (amcl got the map and a scan)')
        self.wait(lambda: self.tf_buffer.can_transform('map', 'base_footprint', rospy.Time(0)),
                  'the map -> odom -> base_footprint TF')
        dxy0, dyaw0 = self.error()
        rospy.loginfo('amcl error after its first update %.3f m %.3f rad', dxy0, dyaw0)
        self.cmd_pub = rospy.Publisher('/diffbot_controller/cmd_vel', Twist, queue_size=1)
        self.wait(lambda: self.cmd_pub.get_num_connections() > 0, 'a subscriber of /diffbot_controller/cmd_vel')
        converged_at, errors, (dxy, dyaw) = self.drive(0.2)
        t_stop = rospy.Time.now().to_sec()
        rospy.wait_for_service('/request_nomotion_update', WALL_TIMEOUT)
        nomotion = rospy.ServiceProxy('/request_nomotion_update', Empty)
        self.wait(lambda: rospy.Time.now().to_sec() > t_stop + 1.0, '1 s of sim time after stopping')
        # no-motion updates on the stopped robot (at least two; the filter is random: more while
        # it is still outside the at-rest tolerance, up to NOMOTION_UPDATES)
        rest_updates, sxy, syaw = self.nomotion_updates(nomotion, 2)
        rospy.loginfo('amcl at rest within tolerance after %d no-motion updates', rest_updates)
        rospy.loginfo('amcl converged after %s s of sim time; tracking max error %.3f m %.3f rad',
                      converged_at, max(e[0] for e in errors), max(e[1] for e in errors))
        self.assertIsNotNone(converged_at, 'amcl did not converge within %.0f s of sim time: error %.3f m %.3f rad'
                             % (CONVERGE_S, dxy, dyaw))
        self.assertLess(max(e[0] for e in errors), DRIVE_XY, 'position error while driving after convergence')
        self.assertLess(max(e[1] for e in errors), DRIVE_YAW, 'yaw error while driving after convergence')
        # the no-motion updates aim at STATIC_*, but without motion the filter adds no noise:
        # once resampling has collapsed the cloud onto its best particle it cannot refine
        # further (a draw in a few dozen lands 0.08-0.10 m off, seen in the gate), so at rest
        # the filter is held to the convergence tolerance
        self.assertLess(sxy, TOL_XY, 'position error at rest after the drive')
        self.assertLess(syaw, TOL_YAW, 'yaw error at rest after the drive')
        with self.lock:
            cloud = self.cloud
        self.assertIsNotNone(cloud, 'no /particlecloud')
        self.assertEqual(cloud.header.frame_id, 'map')
        self.assertGreaterEqual(len(cloud.poses), 100)
        # initialpose 0.5 m / 20 deg off the (now stationary) robot, then no-motion updates
        init = self.initial_pose_off(self.get(model_name='robot').pose)
        init_pub = rospy.Publisher('/initialpose', PoseWithCovarianceStamped, queue_size=1, latch=True)
        self.wait(lambda: init_pub.get_num_connections() > 0, 'amcl subscribing /initialpose')
        init_pub.publish(init)
        # the filter is random: count the updates it takes (typically 3-6), with room for an
        # unlucky draw; the stamps tell that each update has been published. Without motion the
        # filter adds no noise, so once resampling has collapsed the cloud onto the best of the
        # particles drawn around the initial pose it cannot refine further (as the original):
        # that best particle is typically within 0.05 m but, a draw in a few hundred, 0.08-0.11 m
        # off (seen in CI). So at rest the test asks for what no-motion updates guarantee -
        # most of the 0.5 m / 20 deg gone (within the original amcl tests' 0.25 m) - and then,
        # as a user does after a 2D Pose Estimate, drives: the diffusion of motion brings the
        # filter within the convergence tolerance, judged as at the start.
        n, dxy, dyaw = self.nomotion_updates(nomotion, 3)
        rospy.loginfo('amcl recovered from initialpose 0.5 m / 20 deg off after %d no-motion updates: '
                      'error %.3f m %.3f rad', n, dxy, dyaw)
        self.assertLess(dxy, RECOVER_XY, 'position error after initialpose 0.5 m off + %d no-motion updates' % n)
        self.assertLess(dyaw, RECOVER_YAW, 'yaw error after initialpose 20 deg off + %d no-motion updates' % n)
        converged_at, errors, (dxy, dyaw) = self.drive(-0.2)
        rospy.loginfo('after the initialpose, driving: converged after %s s of sim time; max error %.3f m %.3f rad',
                      converged_at, max(e[0] for e in errors), max(e[1] for e in errors))
        self.assertIsNotNone(converged_at, 'amcl did not converge within %.0f s of sim time driving after '
                             'initialpose: error %.3f m %.3f rad' % (CONVERGE_S, dxy, dyaw))


if __name__ == '__main__':
    rospy.init_node('check_amcl_sim')
    rostest.rosrun('amcl', 'check_amcl_sim', AmclOfficeTest)
