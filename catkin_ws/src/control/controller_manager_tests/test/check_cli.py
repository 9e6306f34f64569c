#!/usr/bin/python3
"""rostest: the controller_manager command-line tool and the unspawner against the dummy robot."""
import os
import signal
import subprocess
import unittest

import rospy
import rostest

from cm_check_common import WAIT, CM


def cli(*args):
    """Run `rosrun controller_manager controller_manager ARGS`; (exit code, output)."""
    p = subprocess.run(['rosrun', 'controller_manager', 'controller_manager'] + list(args),
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=WAIT)
    return p.returncode, p.stdout


class CliTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('check_cli')
        cls.cm = CM('/')

    def setUp(self):
        self.cm.clear()

    def test_list_types(self):
        rc, out = cli('lt')
        self.assertEqual(0, rc, out)
        self.assertIn('controller_manager_tests/EffortTestController', out.split())
        rc, out2 = cli('list-types')
        self.assertEqual(out, out2)

    def test_load_start_stop_unload(self):
        rc, out = cli('load', 'effort_j1')
        self.assertEqual((0, "Loaded 'effort_j1'"), (rc, out.strip()))
        rc, out = cli('lc')
        self.assertEqual(0, rc)
        self.assertIn("'effort_j1' - 'hardware_interface::EffortJointInterface' ( initialized )\n", out)
        rc, out = cli('start', 'effort_j1')
        self.assertEqual(0, rc, out)
        self.assertEqual("Started ['effort_j1'] successfully\n", out)
        self.assertIn("'effort_j1' - 'hardware_interface::EffortJointInterface' ( running )\n", cli('list')[1])
        rc, out = cli('stop', 'effort_j1')
        self.assertEqual(0, rc, out)
        self.assertEqual("Stopped ['effort_j1'] successfully\n", out)
        rc, out = cli('unload', 'effort_j1')
        self.assertEqual(0, rc, out)
        self.assertEqual("Unloaded 'effort_j1' successfully\n", out)
        self.assertIn('No controllers are loaded in mechanism control', cli('lc')[1])

    def test_spawn_and_kill(self):
        rc, out = cli('sp', 'velocity_j2', 'state')
        self.assertEqual(0, rc, out)
        self.assertEqual({'velocity_j2': 'running', 'state': 'running'}, self.cm.states())
        rc, out = cli('kl', 'velocity_j2')
        self.assertEqual(0, rc, out)
        self.assertEqual({'state': 'running'}, self.cm.states())
        rc, out = cli('kill', 'state')
        self.assertEqual({}, self.cm.states())

    def test_errors(self):
        rc, out = cli('load', 'unknown_type')
        self.assertEqual(1, rc)
        self.assertIn("Error when loading 'unknown_type'", out)
        rc, out = cli('start', 'not_loaded')
        self.assertEqual(1, rc)
        self.assertIn("Error when starting ['not_loaded'] and stopping []", out)
        rc, out = cli('frobnicate')
        self.assertEqual(1, rc)
        self.assertIn("unknown command 'frobnicate'", out)
        self.assertIn('Commands:', out)

    def test_reload_libraries(self):
        self.assertTrue(self.cm.load('velocity_j2'))
        self.assertTrue(self.cm.load('state'))
        self.assertTrue(self.cm.switch(start=['velocity_j2']))
        rc, out = cli('reload-libraries', '--restore')
        self.assertEqual(0, rc, out)
        self.assertEqual('Restore: True\nSuccessfully reloaded libraries\n'
                         'Controllers restored to original state\n', out)
        self.assertEqual({'velocity_j2': 'running', 'state': 'initialized'}, self.cm.states())
        # As the original script: without --restore the loaded controllers are killed.
        rc, out = cli('reload-libraries')
        self.assertEqual((0, 'Restore: False\nSuccessfully reloaded libraries\n'), (rc, out))
        self.assertEqual({}, self.cm.states())

    def test_unspawner(self):
        self.assertTrue(self.cm.load('velocity_j2'))
        self.assertTrue(self.cm.switch(start=['velocity_j2']))
        p = subprocess.Popen(['rosrun', 'controller_manager', 'unspawner', 'velocity_j2', '__name:=unspawner_test'],
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                             env=dict(os.environ, PYTHONUNBUFFERED='1'))
        try:
            self.cm.wait_states({'velocity_j2': 'stopped'})
        finally:
            p.send_signal(signal.SIGINT)
            try:
                out, _ = p.communicate(timeout=WAIT)
            except subprocess.TimeoutExpired:
                p.kill()
                out, _ = p.communicate()
                self.fail('unspawner did not exit within %.0f s of SIGINT:\n%s' % (WAIT, out))
        self.assertEqual({'velocity_j2': 'running'}, self.cm.states(), out)
        self.assertIn('Restarted controllers: velocity_j2', out)

    def test_controller_group(self):
        """`controller_group list|spawn|switch` over ~controller_groups (here the global one)."""
        rospy.set_param('/controller_groups', {'drive': ['velocity_j2', 'state'],
                                               'arm': ['velocity_j3', 'state'],
                                               'broken': ['unknown_type']})

        def group(*args):
            p = subprocess.run(['rosrun', 'controller_manager', 'controller_group'] + list(args),
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                               timeout=WAIT)
            return p.returncode, p.stdout

        try:
            rc, out = group('list')
            self.assertEqual(0, rc, out)
            self.assertEqual('Number of groups: 3\n  arm\n      velocity_j3\n      state\n'
                             '  broken\n      unknown_type\n  drive\n      velocity_j2\n'
                             '      state\n', out)
            rc, out = group('spawn', 'drive')
            self.assertEqual(0, rc, out)
            self.assertEqual({'velocity_j2': 'running', 'state': 'running'}, self.cm.states())
            rc, out = group('switch', 'arm')
            self.assertEqual(0, rc, out)
            self.assertIn("Loaded 'velocity_j3'", out)
            self.assertIn("Started ['velocity_j3'] successfully", out)
            self.assertIn("Stopped ['velocity_j2'] successfully", out)
            self.assertEqual({'velocity_j2': 'stopped', 'velocity_j3': 'running',
                              'state': 'running'}, self.cm.states())
            rc, out = group('switch', 'broken')
            self.assertEqual(1, rc, out)
            self.assertIn('Cancel group switching', out)
            self.assertEqual('running', self.cm.states()['velocity_j3'])
            rc, out = group('switch', 'nothing')
            self.assertEqual(1, rc, out)
            self.assertIn('There is no controller defined in group nothing', out)
        finally:
            rospy.delete_param('/controller_groups')


if __name__ == '__main__':
    rostest.rosrun('controller_manager_tests', 'check_cli', CliTest)
