#!/usr/bin/python3
"""rostest: multisim.launch's two namespaced simulators, and mimic copying turtlesim1's motion."""
import math
import time
import unittest

import rosgraph
import rospy
import rostest
from geometry_msgs.msg import Twist
from std_srvs.srv import Empty
from turtlesim.msg import Pose

CENTRE = 499.0 / 45.0 / 2.0
ARC_TOLERANCE = 0.03    # m: turtlesim's discrete ticks against the continuous arc


class MultisimTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('check_multisim')
        cls.poses = {}
        for ns in ('turtlesim1', 'turtlesim2'):
            rospy.Subscriber('/%s/turtle1/pose' % ns, Pose,
                             lambda m, ns=ns: cls.poses.__setitem__(ns, m), queue_size=1)
        cls.cmd = rospy.Publisher('/turtlesim1/turtle1/cmd_vel', Twist, queue_size=1)
        deadline = time.monotonic() + 20.0
        while (len(cls.poses) < 2 or cls.cmd.get_num_connections() == 0) \
                and time.monotonic() < deadline:
            time.sleep(0.05)

    def wait(self, predicate, timeout, what):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if predicate():
                return
            time.sleep(0.01)
        self.fail('timed out waiting for ' + what + ' (poses: %s)' % self.poses)

    def reset_both(self):
        for ns in ('turtlesim1', 'turtlesim2'):
            rospy.wait_for_service('/%s/reset' % ns, 10.0)
            rospy.ServiceProxy('/%s/reset' % ns, Empty)()
        self.wait(lambda: all(abs(p.x - CENTRE) < 1e-5 and p.linear_velocity == 0.0
                              for p in self.poses.values()), 5.0, 'both turtles at the centre')
        self.wait(lambda: self.cmd.get_num_connections() > 0, 10.0, 'cmd_vel connection')
        time.sleep(0.3)

    def drive(self, vx, wz):
        t = Twist()
        t.linear.x, t.angular.z = vx, wz
        for _ in range(10):
            self.cmd.publish(t)
            try:
                self.wait(lambda: self.poses['turtlesim2'].linear_velocity > 0.0, 3.0,
                          'the mimic to move turtlesim2')
                break
            except AssertionError:
                continue
        self.wait(lambda: all(p.linear_velocity == 0.0 and p.angular_velocity == 0.0
                              for p in self.poses.values()), 4.0, 'both turtles to stop')
        time.sleep(0.1)
        return self.poses['turtlesim1'], self.poses['turtlesim2']

    def test_namespaces(self):
        master = rosgraph.Master('/check_multisim')
        pubs, subs, srvs = master.getSystemState()
        nodes = {n for _, ns in pubs + subs + srvs for n in ns}
        self.assertTrue({'/turtlesim1/sim', '/turtlesim2/sim', '/mimic'} <= nodes, nodes)
        topics = {t for t, _ in pubs}
        self.assertTrue({'/turtlesim1/turtle1/pose', '/turtlesim2/turtle1/pose',
                         '/turtlesim2/turtle1/cmd_vel'} <= topics, topics)
        services = {s for s, _ in srvs}
        self.assertTrue({'/turtlesim1/spawn', '/turtlesim2/turtle1/set_pen'} <= services)
        self.assertEqual(rospy.get_param('/turtlesim2/sim/background_b'), 255)

    def assert_on_arc(self, pose, radius, what):
        """A turtle that started at the centre heading 0 and drove v/w = radius: its position
        is where its heading puts it on that circle (turtlesim's 16 ms ticks stay within a few
        mm of it)."""
        self.assertAlmostEqual(pose.x - CENTRE, radius * math.sin(pose.theta), delta=ARC_TOLERANCE,
                               msg=what)
        self.assertAlmostEqual(pose.y - CENTRE, radius * (1 - math.cos(pose.theta)),
                               delta=ARC_TOLERANCE, msg=what)

    def test_mimic_copies_motion(self):
        self.reset_both()
        leader, follower = self.drive(1.0, 0.8)
        self.assertGreater(leader.x - CENTRE, 0.5)
        self.assertGreater(leader.theta, 0.5)
        # the follower drives what mimic relays, the leader's velocities: the same arc of
        # radius 1 / 0.8 m. How far along it each turtle got depends on how many 16 ms ticks its
        # simulator ran in its 1 s command window — the machine's load, so not compared.
        self.assert_on_arc(leader, 1.0 / 0.8, 'turtlesim1 on its arc')
        self.assertGreater(follower.theta, 0.3, 'turtlesim2 turned with turtlesim1')
        self.assert_on_arc(follower, 1.0 / 0.8, 'turtlesim2 on the same arc')

    def test_mimic_reverse_is_forward(self):
        self.reset_both()
        leader, follower = self.drive(-1.0, 0.0)
        self.assertLess(leader.x, CENTRE - 0.5)
        # turtlesim's pose reports |v|, so mimic drives the follower forward: +x, straight
        self.assertGreater(follower.x - CENTRE, 0.3)
        self.assertAlmostEqual(follower.y, CENTRE, delta=1e-4)
        self.assertEqual(follower.theta, 0.0)


if __name__ == '__main__':
    rostest.rosrun('turtlesim', 'multisim', MultisimTest)
