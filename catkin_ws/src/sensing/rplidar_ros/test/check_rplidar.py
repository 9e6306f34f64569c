#!/usr/bin/python3
"""rostest: rplidarNode decodes the emulated A1 exactly (standard mode), follows the room in
express mode with angle compensation despite garbage, and reconnects after an unplug."""
import math
import time
import unittest

import numpy as np
import rospy
import rostest
from sensor_msgs.msg import LaserScan
from std_srvs.srv import Empty

from rplidar_ros.emulator import A1Device, Room

TIMEOUT = 60.0    # wall seconds for every wait


class Collector:
    def __init__(self, topic):
        self.msgs = []
        self.stamps = []
        rospy.Subscriber(topic, LaserScan, self.cb)

    def cb(self, msg):
        self.msgs.append(msg)
        self.stamps.append(time.monotonic())

    def wait(self, n, what):
        end = time.monotonic() + TIMEOUT
        while len(self.msgs) < n and time.monotonic() < end:
            time.sleep(0.05)
        if len(self.msgs) < n:
            raise AssertionError('%s: %d scans within %.0f s, expected %d'
                                 % (what, len(self.msgs), TIMEOUT, n))


class RplidarTest(unittest.TestCase):
    def test_a_standard_exact(self):
        c = Collector('/a/scan')
        c.wait(3, '/a/scan')
        dev = A1Device(Room())
        n = dev.samples_per_rev(dev.std_us)
        angles = [(k * 360 * 64) // n for k in range(n)]
        expect = np.array([dev.dist_q2(a) / 4.0 / 1000.0 for a in angles][::-1], np.float32)
        full = [m for m in c.msgs if len(m.ranges) == n]
        self.assertTrue(full, 'no complete scan of %d samples (sizes %s)'
                        % (n, [len(m.ranges) for m in c.msgs]))
        m = full[-1]
        self.assertEqual(m.header.frame_id, 'laser')
        got = np.array(m.ranges, np.float32)
        self.assertTrue(np.array_equal(got, expect),
                        'ranges differ at %s' % np.nonzero(got != expect)[0][:10])
        self.assertAlmostEqual(m.angle_max, math.pi, places=5)
        self.assertAlmostEqual(m.angle_min, math.pi - math.radians(angles[-1] / 64.0), places=3)
        self.assertEqual(m.range_min, np.float32(0.15))
        self.assertEqual(m.range_max, 16.0)

    def test_b_express_compensated_garbage_reconnect(self):
        c = Collector('/b/scan')
        c.wait(5, '/b/scan')
        room = Room()
        m = c.msgs[-1]
        self.assertAlmostEqual(m.angle_min, -math.pi, places=5)
        self.assertAlmostEqual(m.angle_max, math.pi, places=5)
        self.assertEqual(len(m.ranges), int(360 * (400 / 360.0 + 1)))
        err = []
        for i, r in enumerate(m.ranges):
            if math.isfinite(r):
                err.append(abs(r - room.distance(m.angle_min + i * m.angle_increment)))
        self.assertGreater(len(err), 0.8 * len(m.ranges))
        self.assertLess(float(np.median(err)), 0.01)
        # unplug, wait for the gap, expect scans again
        rospy.wait_for_service('/b/rplidar_emulator/unplug', TIMEOUT)
        rospy.ServiceProxy('/b/rplidar_emulator/unplug', Empty)()
        t_unplug = time.monotonic()
        before = len(c.msgs)
        end = time.monotonic() + TIMEOUT
        while time.monotonic() < end and not (
                len(c.msgs) > before + 3 and c.stamps[-1] - t_unplug > 1.0):
            time.sleep(0.05)
        self.assertGreater(len(c.msgs), before + 3, 'no scans after the emulated unplug')
        gaps = np.diff(c.stamps[before - 1:])
        self.assertGreater(float(gaps.max()), 0.8, 'no gap seen: the device did not vanish')


if __name__ == '__main__':
    rospy.init_node('check_rplidar')
    rostest.rosrun('rplidar_ros', 'rplidar_node', RplidarTest)
