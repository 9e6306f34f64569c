#!/usr/bin/env python3
"""bringup_sim.test: gmapping.launch sim:=true teleop:=false. The EKF is the publisher of `odom`
(robot_localization's odometry/filtered remapped), Madgwick's filter publishes imu/data, the
robot turns on /diffbot_controller/cmd_vel until slam_gmapping publishes a map with walls and the
map -> odom transform, and `rosrun map_server map_saver -f` writes it."""
import os
import subprocess
import tempfile
import time
import unittest

import rosgraph
import rospy
import rostest
from course_testing import wait_for
import tf2_ros
from geometry_msgs.msg import Twist
from nav_msgs.msg import OccupancyGrid, Odometry
from sensor_msgs.msg import Imu

WALL_TIMEOUT = 240.0


def wait(cond, what, timeout=WALL_TIMEOUT):
    wait_for(lambda: rospy.is_shutdown() or cond(), timeout, 0.1, what)
    assert not rospy.is_shutdown(), 'shut down while waiting for %s' % what


class BringupSim(unittest.TestCase):
    def publishers(self, topic):
        pubs, _subs, _srvs = rosgraph.Master('/check').getSystemState()
        return next((nodes for t, nodes in pubs if t == topic), [])

    def test_mapping_in_simulation(self):
        got = {}
        for topic, typ in (('/odom', Odometry), ('/imu/data', Imu), ('/map', OccupancyGrid)):
            rospy.Subscriber(topic, typ, lambda m, t=topic: got.__setitem__(t, m), queue_size=1)
        wait(lambda: '/odom' in got, 'odom from the EKF')
        self.assertEqual(self.publishers('/odom'), ['/ekf_loc_node'])
        self.assertEqual(got['/odom'].header.frame_id, 'odom')
        wait(lambda: '/imu/data' in got, 'imu/data from imu_filter_node')
        self.assertEqual(self.publishers('/imu/data'), ['/imu_filter_node'])
        q = got['/imu/data'].orientation
        self.assertAlmostEqual(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w, 1.0, places=3)

        pub = rospy.Publisher('/diffbot_controller/cmd_vel', Twist, queue_size=1)
        wait(lambda: pub.get_num_connections() > 0, 'diffbot_controller listening')
        cmd = Twist()
        cmd.angular.z = 0.8
        # turn on the spot until slam_gmapping publishes a map made after 4 s of turning (3.2 rad:
        # the lidar has seen the room). gmapping updates its map only on a processed scan (one
        # per angularUpdate of turning) once map_update_interval has passed, so a map asked for
        # after the robot stopped may never come: the update due at 5.6 s of a 6 s turn fell
        # before the stop or after it, depending on the machine (a Debian 13 container run)
        start = rospy.get_time()
        deadline = time.monotonic() + WALL_TIMEOUT

        def mapped():
            return '/map' in got and got['/map'].header.stamp.to_sec() >= start + 4.0
        while not mapped():
            self.assertFalse(rospy.is_shutdown(), 'shut down while turning')
            self.assertLess(time.monotonic(), deadline, 'no map from slam_gmapping after %.0f s '
                            'of turning (%.1f s of sim time)' % (WALL_TIMEOUT, rospy.get_time() - start))
            pub.publish(cmd)
            rospy.sleep(0.05)
        pub.publish(Twist())
        m = got['/map']
        occupied = sum(1 for v in m.data if v == 100)
        free = sum(1 for v in m.data if v == 0)
        self.assertGreater(occupied, 100, 'walls in the map (%d occupied, %d free cells)' % (occupied, free))
        self.assertGreater(free, 1000, 'free floor in the map')
        buf = tf2_ros.Buffer()
        tf2_ros.TransformListener(buf)
        wait(lambda: buf.can_transform('map', 'base_link', rospy.Time(0)), 'map -> base_link')

        with tempfile.TemporaryDirectory(prefix='bringup_map_') as tmp:
            out = os.path.join(tmp, 'mymap')
            r = subprocess.run(['rosrun', 'map_server', 'map_saver', '-f', out], capture_output=True,
                               text=True, timeout=120)
            self.assertEqual(r.returncode, 0, r.stdout + r.stderr)
            self.assertTrue(os.path.exists(out + '.pgm') and os.path.exists(out + '.yaml'), os.listdir(tmp))


if __name__ == '__main__':
    rospy.init_node('check', anonymous=True)
    rostest.rosrun('space_scanner_bringup', 'check_bringup_sim', BringupSim)
