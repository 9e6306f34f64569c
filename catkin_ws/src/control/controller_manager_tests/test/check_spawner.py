#!/usr/bin/python3
"""rostest: the spawner script (launch-started ones, SIGINT teardown, YAML files, --wait-for,
--stopped, a missing controller manager)."""
import os
import signal
import subprocess
import tempfile
import time
import unittest

import rospy
import rostest
from std_msgs.msg import Bool

from cm_check_common import WAIT, CM, RosoutWatcher


def spawner(*args, name):
    return subprocess.Popen(['rosrun', 'controller_manager', 'spawner'] + list(args) + ['__name:=' + name],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            env=dict(os.environ, PYTHONUNBUFFERED='1'))


def stop(proc, sig=signal.SIGINT):
    """Send ``sig`` and wait (bounded) for the process; its output."""
    proc.send_signal(sig)
    try:
        out, _ = proc.communicate(timeout=WAIT)
    except subprocess.TimeoutExpired:
        proc.kill()
        out, _ = proc.communicate()
        raise AssertionError('spawner did not exit within %.0f s of signal %d:\n%s' % (WAIT, sig, out))
    return out


def wait_exit(proc):
    try:
        out, _ = proc.communicate(timeout=WAIT)
    except subprocess.TimeoutExpired:
        proc.kill()
        out, _ = proc.communicate()
        raise AssertionError('spawner did not exit by itself within %.0f s:\n%s' % (WAIT, out))
    return out


class SpawnerTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('check_spawner')
        cls.rosout = RosoutWatcher()
        cls.cm = CM('/')
        # the two spawners of the launch file
        cls.launched = {'velocity_j2': 'running', 'state': 'running', 'velocity_j3': 'initialized'}
        cls.cm.wait_states(cls.launched)

    def test_launch_spawners(self):
        self.assertEqual('running', self.cm.states()['velocity_j2'])
        self.assertEqual('initialized', self.cm.states()['velocity_j3'])   # --stopped

    def test_namespaced_manager(self):
        CM('/robot2').wait_states({'velocity_j3': 'running', 'state': 'running'})
        self.assertNotIn('velocity_j3', [n for n, s in self.cm.states().items() if s == 'running'])

    def test_sigint_stops_and_unloads(self):
        p = spawner('effort_j1', name='spawner_sigint')
        try:
            self.cm.wait_states(dict(self.launched, effort_j1='running'))
        finally:
            out = stop(p)
        self.assertEqual(self.launched, self.cm.states(), out)
        for line in ('Loading controller: effort_j1', 'Controller Spawner: Loaded controllers: effort_j1',
                     'Started controllers: effort_j1',
                     'Shutting down spawner. Stopping and unloading controllers...',
                     'Trying to unload effort_j1', 'Succeeded in unloading effort_j1'):
            self.assertIn(line, out)

    def test_yaml_file_argument(self):
        with tempfile.NamedTemporaryFile('w', suffix='.yaml', delete=False) as f:
            f.write('yaml_ctrl:\n  type: controller_manager_tests/VelocityTestController\n'
                    '  joints: [joint1]\n  velocity: 0.25\n')
        try:
            p = spawner(f.name, '--namespace', '/', name='spawner_yaml')
            try:
                self.cm.wait_states(dict(self.launched, yaml_ctrl='running'))
                self.assertEqual('controller_manager_tests/VelocityTestController',
                                 rospy.get_param('/yaml_ctrl/type'))
            finally:
                stop(p, signal.SIGTERM)
            self.assertEqual(self.launched, self.cm.states())
        finally:
            os.unlink(f.name)

    def test_wait_for_topic(self):
        pub = rospy.Publisher('/spawner_go', Bool, queue_size=1, latch=True)
        p = spawner('--wait-for', '/spawner_go', 'effort_j1', name='spawner_wait_for')
        try:
            deadline = time.monotonic() + WAIT
            while pub.get_num_connections() < 1:   # the spawner subscribed: it is waiting
                self.assertLess(time.monotonic(), deadline, 'the spawner never subscribed to /spawner_go')
                time.sleep(0.05)
            pub.publish(Bool(False))
            self.assertNotIn('effort_j1', self.cm.states())
            pub.publish(Bool(True))
            self.cm.wait_states(dict(self.launched, effort_j1='running'))
        finally:
            out = stop(p)
        self.assertIn('Waiting for /spawner_go to be True', out)
        self.assertEqual(self.launched, self.cm.states())

    def test_failed_load_and_stopped_teardown(self):
        p = spawner('--stopped', 'no_such_controller', 'effort_j1', name='spawner_fail')
        try:
            self.cm.wait_states(dict(self.launched, effort_j1='initialized'))
        finally:
            out = stop(p)
        self.assertIn('Failed to load no_such_controller', out)
        self.rosout.wait_for("Could not load controller 'no_such_controller' because the type was not specified")
        self.assertEqual(self.launched, self.cm.states())

    def test_missing_controller_manager(self):
        p = spawner('--namespace', '/nowhere', '--timeout', '1', 'x', name='spawner_missing')
        out = wait_exit(p)
        self.assertEqual(0, p.returncode, out)
        self.assertIn("Controller Spawner couldn't find the expected controller_manager ROS interface.", out)


if __name__ == '__main__':
    rostest.rosrun('controller_manager_tests', 'check_spawner', SpawnerTest)
