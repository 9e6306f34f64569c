#!/usr/bin/python3
"""rostest: draw_square resets the simulator and drives turtle1 along a 2 m square."""
import math
import time
import unittest

import rospy
import rostest
from turtlesim.msg import Pose

CENTRE = 499.0 / 45.0 / 2.0


class DrawSquareTest(unittest.TestCase):

    def test_square_corners(self):
        rospy.init_node('check_draw_square')
        poses = []
        rospy.Subscriber('/turtle1/pose', Pose, poses.append, queue_size=100)
        corners = [(CENTRE + 2.0, CENTRE, math.pi / 2), (CENTRE + 2.0, CENTRE + 2.0, math.pi),
                   (CENTRE, CENTRE + 2.0, -math.pi / 2)]
        reached = []
        deadline = time.monotonic() + 60.0
        seen = 0
        while len(reached) < len(corners) and time.monotonic() < deadline:
            time.sleep(0.05)
            for p in poses[seen:]:
                cx, cy, heading = corners[len(reached)]
                # at the corner, turned towards the next side, and stopped
                if (abs(p.x - cx) < 0.2 and abs(p.y - cy) < 0.2
                        and abs(math.remainder(p.theta - heading, 2 * math.pi)) < 0.05
                        and p.linear_velocity == 0.0 and p.angular_velocity == 0.0):
                    reached.append(p)
                    if len(reached) == len(corners):
                        break
            seen = len(poses)
        self.assertEqual(len(reached), len(corners),
                         'reached corners %s; last pose %s' % (reached, poses[-1] if poses else None))


if __name__ == '__main__':
    rostest.rosrun('turtlesim', 'draw_square', DrawSquareTest)
