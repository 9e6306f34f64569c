#!/usr/bin/python3
"""rostest: a headless turtlesim_node driven through its topics, services and params."""
import math
import threading
import time
import unittest

import rosgraph
import rospy
import rostest
from geometry_msgs.msg import Twist
from std_srvs.srv import Empty
from turtlesim.msg import Color, Pose
from turtlesim.srv import Kill, SetPen, Spawn, TeleportAbsolute, TeleportRelative

SIZE = 499.0 / 45.0
CENTRE = SIZE / 2.0
BACKGROUND = (69, 86, 255)
PEN = (179, 184, 255)
F32 = 1e-5          # float32 rounding of a pose field


class Latest:
    """The last message of a topic, and a condition variable to wait on new ones."""

    def __init__(self, topic, cls):
        self.cond = threading.Condition()
        self.msg = None
        self.count = 0
        self.sub = rospy.Subscriber(topic, cls, self._cb, queue_size=10)

    def _cb(self, msg):
        with self.cond:
            self.msg = msg
            self.count += 1
            self.cond.notify_all()

    def wait(self, predicate=lambda m: True, timeout=5.0, fresh=True):
        """The first message (newer than the call when `fresh`) that satisfies predicate."""
        deadline = time.monotonic() + timeout
        with self.cond:
            start = self.count
            while True:
                if self.msg is not None and (not fresh or self.count > start) and predicate(self.msg):
                    return self.msg
                left = deadline - time.monotonic()
                if left <= 0:
                    raise AssertionError('no matching message within %.1f s (last: %s)'
                                         % (timeout, self.msg))
                self.cond.wait(left)


def srv(name, cls):
    rospy.wait_for_service(name, 10.0)
    return rospy.ServiceProxy(name, cls)


def system_state():
    master = rosgraph.Master('/check_turtlesim')
    pubs, subs, srvs = master.getSystemState()
    return ({t for t, n in pubs if '/turtlesim' in n}, {t for t, n in subs if '/turtlesim' in n},
            {s for s, n in srvs if '/turtlesim' in n})


class TurtlesimNodeTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('check_turtlesim')
        cls.pose = Latest('/turtle1/pose', Pose)
        cls.color = Latest('/turtle1/color_sensor', Color)
        cls.cmd = rospy.Publisher('/turtle1/cmd_vel', Twist, queue_size=1)
        cls.reset = srv('/reset', Empty)
        cls.clear = srv('/clear', Empty)
        cls.spawn = srv('/spawn', Spawn)
        cls.kill = srv('/kill', Kill)
        cls.pose.wait(timeout=15.0)
        deadline = time.monotonic() + 10.0
        while cls.cmd.get_num_connections() == 0 and time.monotonic() < deadline:
            time.sleep(0.05)

    def setUp(self):
        self.reset()
        # re-created by reset: wait until our subscriptions are connected again
        self.pose.wait(lambda p: abs(p.x - CENTRE) < F32 and p.linear_velocity == 0.0, 10.0)
        deadline = time.monotonic() + 10.0
        while self.cmd.get_num_connections() == 0 and time.monotonic() < deadline:
            time.sleep(0.05)
        self.assertGreater(self.cmd.get_num_connections(), 0, 'cmd_vel not connected after reset')

    def twist(self, vx=0.0, vy=0.0, wz=0.0):
        """Publish one Twist; re-send only if no pose shows it (a connection made stale by the
        previous test's /reset may swallow the first one)."""
        t = Twist()
        t.linear.x, t.linear.y, t.angular.z = vx, vy, wz
        speed = math.hypot(vx, vy)
        for _ in range(10):
            self.sent_at = time.monotonic()
            self.cmd.publish(t)
            try:
                return self.pose.wait(lambda p: abs(p.linear_velocity - speed) < F32
                                      and abs(p.angular_velocity - wz) < F32, 0.5)
            except AssertionError:
                continue
        self.fail('turtle1 never reported the commanded velocity')

    def pen(self, name, r, g, b, width, off):
        srv('/%s/set_pen' % name, SetPen)(r, g, b, width, off)

    def teleport(self, x, y, theta, name='turtle1'):
        srv('/%s/teleport_absolute' % name, TeleportAbsolute)(x, y, theta)

    # --- graph and params ---------------------------------------------------------------
    def test_graph(self):
        pubs, subs, srvs = system_state()
        self.assertTrue({'/turtle1/pose', '/turtle1/color_sensor'} <= pubs, pubs)
        self.assertIn('/turtle1/cmd_vel', subs)
        self.assertTrue({'/clear', '/reset', '/spawn', '/kill', '/turtle1/set_pen',
                         '/turtle1/teleport_absolute', '/turtle1/teleport_relative'} <= srvs, srvs)

    def test_background_params_written_back(self):
        self.assertEqual([rospy.get_param('/turtlesim/background_%s' % c) for c in 'rgb'],
                         list(BACKGROUND))

    def test_initial_pose(self):
        p = self.pose.wait()
        self.assertAlmostEqual(p.x, 5.544445, places=5)
        self.assertAlmostEqual(p.y, 5.544445, places=5)
        self.assertEqual((p.theta, p.linear_velocity, p.angular_velocity), (0.0, 0.0, 0.0))

    # --- motion -------------------------------------------------------------------------
    def test_forward_one_second_then_timeout(self):
        first_sent = time.monotonic()
        moving = self.twist(vx=1.0)
        stopped = self.pose.wait(lambda p: p.linear_velocity == 0.0, 30.0)
        stopped_seen = time.monotonic()
        # turtlesim stops 1 s of wall time after the last command it received, never sooner
        # (how much later depends on the machine's load: no upper bound here)
        self.assertGreaterEqual(stopped_seen - self.sent_at, 0.98, 'cmd_vel timeout is 1 s')
        # each update moves the turtle 0.016 s x 1 m/s along +x: a whole number of ticks
        # (about 62 in the 1 s on an idle machine; fewer when the timer is starved)
        ticks = (stopped.x - CENTRE) / 0.016
        self.assertGreaterEqual(round(ticks), 1)
        self.assertAlmostEqual(ticks, round(ticks), delta=0.01, msg='moved %.4f ticks' % ticks)
        self.assertLessEqual(round(ticks), math.ceil((stopped_seen - first_sent) * 62.5) + 2)
        self.assertAlmostEqual(stopped.y, CENTRE, delta=F32)
        self.assertEqual(stopped.theta, 0.0)
        self.assertGreater(moving.x, CENTRE)
        time.sleep(0.3)
        still = self.pose.wait()
        self.assertEqual((still.x, still.y), (stopped.x, stopped.y), 'turtle kept moving')

    def test_rotation_and_reverse_speed(self):
        self.twist(vx=-1.0, wz=1.0)
        p = self.pose.wait(lambda p: p.angular_velocity == 1.0, 2.0)
        self.assertEqual(p.linear_velocity, 1.0, 'linear_velocity is |v|, >= 0 when reversing')
        p = self.pose.wait(lambda p: p.theta > 0.5, 2.0)
        self.assertLess(p.x, CENTRE)

    def test_holonomic_linear_y(self):
        self.twist(vy=1.0)
        p = self.pose.wait(lambda p: p.y > CENTRE + 0.3, 2.0)
        self.assertAlmostEqual(p.x, CENTRE, delta=F32)
        self.assertEqual(p.theta, 0.0)
        self.assertEqual(p.linear_velocity, 1.0)

    def test_wall_clamp(self):
        self.teleport(10.9, 2.0, 0.0)
        self.pose.wait(lambda p: abs(p.x - 10.9) < F32, 2.0)
        self.twist(vx=2.0)
        p = self.pose.wait(lambda p: p.x >= SIZE - F32, 2.0)
        self.assertAlmostEqual(p.x, SIZE, delta=F32)
        p = self.pose.wait()
        self.assertAlmostEqual(p.x, SIZE, delta=F32)
        self.assertEqual(p.linear_velocity, 2.0, 'the command is kept while pushing the wall')

    # --- teleports ----------------------------------------------------------------------
    def test_teleport_absolute_and_relative(self):
        self.teleport(2.0, 3.0, 1.0)
        p = self.pose.wait(lambda p: abs(p.x - 2.0) < F32, 2.0)
        self.assertAlmostEqual(p.y, 3.0, delta=F32)
        self.assertAlmostEqual(p.theta, 1.0, delta=F32)
        self.teleport(2.0, 3.0, 0.0)
        srv('/turtle1/teleport_relative', TeleportRelative)(1.0, math.pi / 2)
        p = self.pose.wait(lambda p: abs(p.theta - math.pi / 2) < 1e-4, 2.0)
        self.assertAlmostEqual(p.x, 2.0, delta=1e-4)
        self.assertAlmostEqual(p.y, 4.0, delta=1e-4)
        self.teleport(4.0, 20.0, 0.0)   # above the top edge: lands on y = H
        p = self.pose.wait(lambda p: abs(p.x - 4.0) < F32, 2.0)
        self.assertAlmostEqual(p.y, SIZE, delta=F32)

    # --- pen and colour sensor ----------------------------------------------------------
    def test_color_sensor_pen_and_clear(self):
        self.assertEqual(tuple(self.color.wait(timeout=2.0).__getstate__()), BACKGROUND)
        self.twist(vx=1.0)                     # default pen draws under the turtle
        self.pose.wait(lambda p: p.x > CENTRE + 0.3, 2.0)
        c = self.color.wait()
        self.assertEqual((c.r, c.g, c.b), PEN)
        self.twist()
        self.pen('turtle1', 255, 0, 0, 3, 0)
        srv('/turtle1/teleport_relative', TeleportRelative)(0.0, math.pi / 2)
        self.twist(vx=1.0)
        self.pose.wait(lambda p: p.y > CENTRE + 0.3, 2.0)
        c = self.color.wait()
        self.assertEqual((c.r, c.g, c.b), (255, 0, 0))
        self.twist()
        self.pen('turtle1', 0, 0, 0, 0, 1)     # off: no trail under the turtle
        self.teleport(2.0, 2.0, 0.0)
        self.pose.wait(lambda p: abs(p.x - 2.0) < F32, 2.0)
        c = self.color.wait()
        self.assertEqual((c.r, c.g, c.b), BACKGROUND)
        self.pen('turtle1', 0, 255, 0, 5, 0)   # on again, new colour; teleport draws a line
        self.teleport(2.0, 1.0, 0.0)
        self.pose.wait(lambda p: abs(p.y - 1.0) < F32, 2.0)
        c = self.color.wait()
        self.assertEqual((c.r, c.g, c.b), (0, 255, 0))
        self.clear()
        c = self.color.wait()
        self.assertEqual((c.r, c.g, c.b), BACKGROUND)

    def test_clear_rereads_background(self):
        try:
            for c, v in zip('rgb', (10, 20, 30)):
                rospy.set_param('/turtlesim/background_' + c, v)
            self.assertEqual(tuple(self.color.wait().__getstate__()), BACKGROUND,
                             'params are only read on clear')
            self.clear()
            c = self.color.wait()
            self.assertEqual((c.r, c.g, c.b), (10, 20, 30))
        finally:
            for c, v in zip('rgb', BACKGROUND):
                rospy.set_param('/turtlesim/background_' + c, v)
            self.clear()

    # --- spawn / kill / reset -----------------------------------------------------------
    def test_spawn_kill(self):
        self.assertEqual(self.spawn(1.0, 2.0, 0.5, '').name, 'turtle2')
        self.assertEqual(self.spawn(3.0, 2.0, 0.0, 'leo').name, 'leo')
        self.assertEqual(self.spawn(3.0, 4.0, 0.0, '').name, 'turtle3')
        with self.assertRaises(rospy.ServiceException) as err:
            self.spawn(1.0, 1.0, 0.0, 'leo')
        self.assertIn('A turtled named [leo] already exists', str(err.exception))
        leo = Latest('/leo/pose', Pose).wait(timeout=5.0)
        self.assertAlmostEqual(leo.x, 3.0, delta=F32)
        t2 = Latest('/turtle2/pose', Pose).wait(timeout=5.0)
        self.assertAlmostEqual(t2.theta, 0.5, delta=F32)
        pubs, subs, srvs = system_state()
        self.assertIn('/leo/pose', pubs)
        self.assertIn('/leo/teleport_absolute', srvs)

        self.kill('leo')
        pubs, subs, srvs = system_state()
        self.assertFalse([n for n in pubs | subs | srvs if n.startswith('/leo/')],
                         'topics/services of a killed turtle remain')
        self.assertIn('/turtle2/pose', pubs)
        with self.assertRaises(rospy.ServiceException) as err:
            self.kill('leo')
        self.assertIn('Tried to kill turtle [leo], which does not exist', str(err.exception))
        with self.assertRaises(rospy.ServiceException):
            self.spawn(1.0, 1.0, 0.0, 'bad name!')

    def test_reset(self):
        self.spawn(1.0, 1.0, 0.0, 'raph')
        self.teleport(1.0, 1.0, 2.0)
        self.pose.wait(lambda p: abs(p.x - 1.0) < F32, 2.0)
        self.reset()
        p = self.pose.wait(lambda p: abs(p.x - CENTRE) < F32, 5.0)
        self.assertAlmostEqual(p.y, CENTRE, delta=F32)
        self.assertEqual(p.theta, 0.0)
        pubs, _, srvs = system_state()
        self.assertEqual({t for t in pubs if t.endswith('/pose')}, {'/turtle1/pose'})
        self.assertNotIn('/raph/set_pen', srvs)
        self.assertEqual(self.spawn(1.0, 1.0, 0.0, '').name, 'turtle2', 'counter restarts')


if __name__ == '__main__':
    rostest.rosrun('turtlesim', 'turtlesim_node', TurtlesimNodeTest)
