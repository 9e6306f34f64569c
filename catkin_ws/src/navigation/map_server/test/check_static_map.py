#!/usr/bin/python3
"""rostest node (static_map.test): map_server started on test/testmap.bmp with resolution 0.1
serves navigation's 10 x 10 test map on static_map, publishes it latched on map and
map_metadata, and change_map loads another map (a YAML) or answers 255 for a missing one."""
import os
import sys
import tempfile
import unittest

import numpy as np
import rospy
import rostest
from nav_msgs.msg import MapMetaData, OccupancyGrid
from nav_msgs.srv import GetMap, LoadMap

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from make_fixtures import TESTMAP  # noqa: E402

WAIT = 60.0     # wall seconds: the node's start on a busy machine


class StaticMapTest(unittest.TestCase):
    def test_static_map_topics_and_change_map(self):
        rospy.wait_for_service('static_map', WAIT)
        resp = rospy.ServiceProxy('static_map', GetMap)()
        info = resp.map.info
        self.assertAlmostEqual(info.resolution, 0.1, places=6)
        self.assertEqual((info.width, info.height), (10, 10))
        self.assertEqual(list(resp.map.data), [v for row in TESTMAP for v in row])
        self.assertEqual(resp.map.header.frame_id, 'map')

        latched = rospy.wait_for_message('map', OccupancyGrid, WAIT)
        self.assertEqual(list(latched.data), list(resp.map.data))
        meta = rospy.wait_for_message('map_metadata', MapMetaData, WAIT)
        self.assertEqual((meta.width, meta.height), (10, 10))

        change = rospy.ServiceProxy('change_map', LoadMap)
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, 'two.yaml')
            with open(path, 'w') as f:
                f.write('image: %s\nresolution: 0.5\norigin: [1.0, 2.0, 0.0]\nnegate: 1\n'
                        'occupied_thresh: 0.65\nfree_thresh: 0.196\n' % os.path.join(HERE, 'testmap.png'))
            self.assertEqual(change(path).result, 0)
            grid = rospy.ServiceProxy('static_map', GetMap)().map
            self.assertEqual((grid.info.resolution, grid.info.origin.position.x), (0.5, 1.0))
            negated = [0 if v == 100 else 100 for row in TESTMAP for v in row]
            self.assertEqual(list(grid.data), negated)
            self.assertEqual(change(os.path.join(d, 'missing.yaml')).result, 255)
        self.assertEqual(np.asarray(rospy.ServiceProxy('static_map', GetMap)().map.data).tolist(), negated)


if __name__ == '__main__':
    rospy.init_node('static_map_test')
    rostest.rosrun('map_server', 'static_map', StaticMapTest)
