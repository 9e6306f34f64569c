#!/usr/bin/python3
"""slam_office.test: drive the space scanner in room B of the office for a few simulated seconds
(a turn on the spot, then 1 m ahead), then
- slam_gmapping's map marks >= 85 % of the observed wall faces within one cell, <= 3 % of its
  occupied cells are away from walls and furniture, ~entropy and map->odom are published;
- `rosrun map_server map_saver -f DIR/office` writes office.pgm + office.yaml;
- `rosrun map_server map_server DIR/office.yaml` serves the identical grid back (static_map)."""
import os
import shutil
import subprocess
import sys
import tempfile
import threading
import time
import unittest

import numpy as np
import rospy
import rostest
import tf2_ros
from gazebo_msgs.srv import GetModelState
from geometry_msgs.msg import Twist
from nav_msgs.srv import GetMap
from rospy.numpy_msg import numpy_msg
from nav_msgs.msg import OccupancyGrid
from std_msgs.msg import Float64

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import office_walls  # noqa: E402

WALL_TIMEOUT = 200.0
# the diploma's gmapping.launch parameters; a 20 x 20 m map; a fixed seed
SLAM_ARGS = ['_map_update_interval:=1.0', '_maxUrange:=6.0', '_maxRange:=8.0', '_linearUpdate:=0.05',
             '_angularUpdate:=0.5', '_base_frame:=base_footprint', '_xmin:=-10', '_ymin:=-10', '_xmax:=10',
             '_ymax:=10', '_seed:=1', '__name:=slam_gmapping']
WALLS_FOUND_MIN = 0.85
FALSE_OCCUPIED_MAX = 0.03


class SimDriving:
    """wait for a condition (wall-time hang guard) and drive cmd_vel for sim seconds; shared with
    check_slam_replay.py (with its own wall_timeout)."""
    wall_timeout = WALL_TIMEOUT

    def wait(self, cond, what, timeout=None):
        timeout = self.wall_timeout if timeout is None else timeout
        end = time.monotonic() + timeout
        while not cond():
            if rospy.is_shutdown() or time.monotonic() > end:
                self.fail('timed out (%.0f s wall) waiting for %s' % (timeout, what))
            time.sleep(0.05)

    def drive(self, pub, vx, wz, seconds):
        cmd = Twist()
        cmd.linear.x, cmd.angular.z = vx, wz
        t_end = rospy.Time.now().to_sec() + seconds
        end = time.monotonic() + self.wall_timeout
        while rospy.Time.now().to_sec() < t_end:
            self.assertLess(time.monotonic(), end, 'sim time stalled while driving')
            pub.publish(cmd)
            rospy.sleep(0.02)


class SlamOfficeTest(SimDriving, unittest.TestCase):
    def setUp(self):
        self.lock = threading.Lock()
        self.map = None
        self.map_count = 0
        self.entropy = None
        rospy.Subscriber('/map', numpy_msg(OccupancyGrid), self.on_map, queue_size=1, buff_size=2 ** 26)
        rospy.Subscriber('/slam_gmapping/entropy', Float64, self.on_entropy, queue_size=1)
        self.tf_buffer = tf2_ros.Buffer()
        self.tf_listener = tf2_ros.TransformListener(self.tf_buffer)
        self.procs = []
        self.tmp = tempfile.mkdtemp(prefix='slam_office_')

    def tearDown(self):
        for p in self.procs:
            if p.poll() is None:
                p.terminate()
                try:
                    p.wait(10)
                except subprocess.TimeoutExpired:
                    p.kill()
                    p.wait()
        shutil.rmtree(self.tmp, ignore_errors=True)

    def on_map(self, msg):
        with self.lock:
            self.map = msg
            self.map_count += 1

    def on_entropy(self, msg):
        self.entropy = msg.data

    def test_map_save_serve(self):
        pub = rospy.Publisher('/diffbot_controller/cmd_vel', Twist, queue_size=1)
        self.wait(lambda: pub.get_num_connections() > 0, 'diffbot_controller subscribing /diffbot_controller/cmd_vel')
        rospy.wait_for_service('/gazebo/get_model_state', WALL_TIMEOUT)
        get = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)
        self.wait(lambda: get(model_name='robot').success and get(model_name='robot').pose.position.z < 0.05,
                  'the robot landing on its wheels')
        self.drive(pub, 0.0, 0.0, 1.0)            # settle after landing
        self.procs.append(subprocess.Popen(['rosrun', 'gmapping', 'slam_gmapping'] + SLAM_ARGS))
        self.wait(lambda: self.map is not None, 'the first map from slam_gmapping')
        self.drive(pub, 0.0, 0.8, 8.0)            # one turn on the spot
        n = self.map_count
        self.drive(pub, 0.3, 0.0, 3.5)            # 1 m towards the door of room B
        self.drive(pub, 0.0, 0.0, 2.0)
        # maps come every map_update_interval (1 s) of processed scans: some during the 1 m
        self.wait(lambda: self.map_count > n, 'a map during the last drive')
        with self.lock:
            msg = self.map
        self.assertIsNotNone(self.entropy, 'no ~entropy message')
        tf = self.tf_buffer.lookup_transform('map', 'odom', rospy.Time(0), rospy.Duration(10.0))
        self.assertEqual(tf.child_frame_id, 'odom')
        info = msg.info
        self.assertAlmostEqual(info.resolution, 0.05, places=6)
        self.assertEqual((info.width, info.height), (400, 400))
        data = np.asarray(msg.data, dtype=np.int8).reshape(info.height, info.width)
        sdf, world = office_walls.office_paths()
        boxes = office_walls.wall_boxes(sdf)
        found, false_occ, seen = office_walls.map_quality(
            data, (info.origin.position.x, info.origin.position.y), info.resolution, boxes,
            office_walls.furniture(world))
        rospy.loginfo('slam_office: %d observed wall face points, %.1f %% marked within one cell, '
                      '%.2f %% false occupied', seen, 100 * found, 100 * false_occ)
        if os.environ.get('SLAM_OFFICE_DUMP'):
            np.save(os.environ['SLAM_OFFICE_DUMP'], data)
        self.assertGreater(seen, 300, 'too few wall faces observed (%d points)' % seen)
        self.assertGreaterEqual(found, WALLS_FOUND_MIN,
                                'only %.1f %% of the observed wall faces marked' % (100 * found))
        self.assertLessEqual(false_occ, FALSE_OCCUPIED_MAX, '%.2f %% false occupied cells (%.1f %% of walls marked)'
                             % (100 * false_occ, 100 * found))

        # map_saver -> files; map_server -> the same grid back
        env = dict(os.environ)
        base = os.path.join(self.tmp, 'office')
        saver = subprocess.run(['rosrun', 'map_server', 'map_saver', '-f', base], env=env, timeout=120,
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
        self.assertEqual(saver.returncode, 0, 'map_saver failed:\n%s' % saver.stdout)
        for line in ('Waiting for the map', 'Received a 400 X 400 map @ 0.050 m/pix',
                     'Writing map occupancy data to %s.pgm' % base, 'Done'):
            self.assertIn(line, saver.stdout)
        with open(base + '.yaml') as f:
            self.assertTrue(f.read().startswith('image: %s.pgm\nresolution: 0.050000\n' % base))
        with self.lock:
            saved = np.asarray(self.map.data, dtype=np.int8).reshape(info.height, info.width)
        server = subprocess.Popen(['rosrun', 'map_server', 'map_server', base + '.yaml',
                                   'static_map:=/served/static_map', 'map:=/served/map',
                                   'map_metadata:=/served/map_metadata'], env=env)
        self.procs.append(server)
        rospy.wait_for_service('/served/static_map', 60.0)
        served = rospy.ServiceProxy('/served/static_map', GetMap)().map
        self.assertEqual((served.info.width, served.info.height), (400, 400))
        self.assertAlmostEqual(served.info.origin.position.x, info.origin.position.x, places=5)
        back = np.asarray(served.data, dtype=np.int8).reshape(400, 400)
        self.assertTrue(np.array_equal(back, saved), '%d cells differ after map_saver -> map_server'
                        % int(np.sum(back != saved)))


if __name__ == '__main__':
    rospy.init_node('check_slam_office')
    rostest.rosrun('gmapping', 'check_slam_office', SlamOfficeTest)
