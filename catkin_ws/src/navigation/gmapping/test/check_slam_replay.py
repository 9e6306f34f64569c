#!/usr/bin/python3
"""slam_replay.test: record a bag of the space scanner driving in the office (/scan, /tf,
/tf_static with `rosbag record`), then run `rosrun gmapping slam_gmapping_replay` on it twice with
the same --seed and an --on_done that saves the map with map_saver:
- each run exits 0 after on_done, publishing map (in its namespace) and TF map->odom as it goes;
- the two saved maps are identical, byte for byte;
- the map marks >= 85 % of the observed wall faces within one cell, <= 3 % false occupied."""
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import unittest

import rospy
import rostest
import tf2_ros
from gazebo_msgs.srv import GetModelState
from geometry_msgs.msg import Twist
from nav_msgs.msg import OccupancyGrid

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import office_walls  # noqa: E402
from map_server import map_io  # noqa: E402
from check_slam_office import SLAM_ARGS, WALLS_FOUND_MIN, FALSE_OCCUPIED_MAX, SimDriving  # noqa: E402

WALL_TIMEOUT = 300.0
SEED = 7


class SlamReplayTest(SimDriving, unittest.TestCase):
    wall_timeout = WALL_TIMEOUT

    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix='slam_replay_')
        self.procs = []
        self.lock = threading.Lock()
        self.maps = {}
        self.tf_buffer = tf2_ros.Buffer(rospy.Duration(600.0))
        self.tf_listener = tf2_ros.TransformListener(self.tf_buffer)

    def tearDown(self):
        for p in self.procs:
            if p.poll() is None:
                os.killpg(p.pid, signal.SIGINT)
                try:
                    p.wait(15)
                except subprocess.TimeoutExpired:
                    os.killpg(p.pid, signal.SIGKILL)
                    p.wait()
        shutil.rmtree(self.tmp, ignore_errors=True)

    def popen(self, cmd, **kw):
        p = subprocess.Popen(cmd, start_new_session=True, **kw)
        self.procs.append(p)
        return p

    def record(self, bag):
        pub = rospy.Publisher('/diffbot_controller/cmd_vel', Twist, queue_size=1)
        self.wait(lambda: pub.get_num_connections() > 0, 'diffbot_controller subscribing cmd_vel')
        rospy.wait_for_service('/gazebo/get_model_state', WALL_TIMEOUT)
        get = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState)
        self.wait(lambda: get(model_name='robot').pose.position.z < 0.05, 'the robot landing')
        self.drive(pub, 0.0, 0.0, 1.0)
        rec = self.popen(['rosbag', 'record', '-O', bag, '/scan', '/tf', '/tf_static'],
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        self.wait(lambda: os.path.exists(bag + '.active'), 'rosbag record starting')
        self.drive(pub, 0.0, 0.0, 1.0)            # the recorder's subscriptions connect
        self.drive(pub, 0.0, 0.8, 8.0)            # one turn on the spot
        self.drive(pub, 0.3, 0.0, 3.5)            # 1 m towards the door of room B
        self.drive(pub, 0.0, 0.0, 1.0)
        os.killpg(rec.pid, signal.SIGINT)
        rec.wait(60)
        self.assertTrue(os.path.exists(bag), 'rosbag record wrote no %s' % bag)

    def on_map(self, name):
        def cb(msg):
            with self.lock:
                self.maps[name] = msg
        return cb

    def replay(self, bag, name):
        base = os.path.join(self.tmp, name)
        rospy.Subscriber('/%s/map' % name, OccupancyGrid, self.on_map(name), queue_size=1,
                         buff_size=2 ** 26)
        on_done = 'rosrun map_server map_saver -f %s map:=/%s/map __name:=saver_%s' % (base, name, name)
        log = open(base + '.log', 'w')
        p = self.popen(['rosrun', 'gmapping', 'slam_gmapping_replay', '--bag_filename', bag,
                        '--scan_topic', '/scan', '--seed', str(SEED), '--on_done', on_done,
                        '__ns:=' + name] + [a for a in SLAM_ARGS if not a.startswith('__name')],
                       stdout=log, stderr=subprocess.STDOUT)
        try:
            rc = p.wait(WALL_TIMEOUT)
        except subprocess.TimeoutExpired:
            self.fail('slam_gmapping_replay did not finish within %.0f s' % WALL_TIMEOUT)
        log.close()
        with open(base + '.log') as f:
            out = f.read()
        self.assertEqual(rc, 0, 'slam_gmapping_replay exited %d:\n%s' % (rc, out[-3000:]))
        for line in ('replay stopped.', 'Writing map occupancy data to %s.pgm' % base):
            self.assertIn(line, out)
        return base, out

    def test_replay_twice_same_seed_same_map(self):
        bag = os.path.join(self.tmp, 'office.bag')
        self.record(bag)
        a, out_a = self.replay(bag, 'run_a')
        # TF map->odom went out while replaying
        tf = self.tf_buffer.lookup_transform('map', 'odom', rospy.Time(0), rospy.Duration(10.0))
        self.assertEqual(tf.child_frame_id, 'odom')
        self.wait(lambda: 'run_a' in self.maps, 'a map on /run_a/map', 30)
        b, _ = self.replay(bag, 'run_b')
        with open(a + '.pgm', 'rb') as fa, open(b + '.pgm', 'rb') as fb:
            pa, pb = fa.read(), fb.read()
        self.assertEqual(pa, pb, 'the two replays with seed %d saved different maps' % SEED)
        m = map_io.load_map(a + '.yaml')     # map_server's reading: rows from the bottom
        self.assertEqual(m.data.shape, (400, 400))
        grid = m.data
        sdf, world = office_walls.office_paths()
        found, false_occ, seen = office_walls.map_quality(
            grid, tuple(m.origin[:2]), m.resolution, office_walls.wall_boxes(sdf),
            office_walls.furniture(world))
        rospy.loginfo('slam_replay: %d observed wall face points, %.1f %% marked within one cell, '
                      '%.2f %% false occupied', seen, 100 * found, 100 * false_occ)
        self.assertGreater(seen, 300)
        self.assertGreaterEqual(found, WALLS_FOUND_MIN)
        self.assertLessEqual(false_occ, FALSE_OCCUPIED_MAX)


if __name__ == '__main__':
    rospy.init_node('check_slam_replay')
    rostest.rosrun('gmapping', 'check_slam_replay', SlamReplayTest)
