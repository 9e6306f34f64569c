#!/usr/bin/python3
"""rostest: every controller_manager service against the dummy robot."""
import unittest

import rospy
import rostest

from cm_check_common import BEST_EFFORT, CM, STRICT, Latest, RosoutWatcher

TEST_TYPES = ['controller_manager_tests/EffortTestController', 'controller_manager_tests/VelocityTestController',
              'controller_manager_tests/StateTestController', 'controller_manager_tests/ImuTestController',
              'controller_manager_tests/MultiTestController',
              'controller_manager_tests/CompatTestController']   # exported with pluginlib/class_list_macros.h


class ServicesTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node('check_services')
        cls.rosout = RosoutWatcher()
        cls.cm = CM('/')
        cls.commands = Latest('/dummy_robot_hw/commands')

    def setUp(self):
        self.cm.clear()

    def test_list_controller_types(self):
        resp = self.cm.types_srv()
        for t in TEST_TYPES:
            self.assertIn(t, resp.types)
        self.assertEqual(len(resp.types), len(resp.base_classes))
        self.assertEqual({'controller_interface::ControllerBase'}, set(resp.base_classes))

    def test_load_errors(self):
        self.assertFalse(self.cm.load('unknown_type'))
        self.rosout.wait_for("Could not load controller 'unknown_type' because controller type "
                             "'no_such_pkg/NoSuchController' does not exist.")
        self.rosout.wait_for("Use 'rosservice call controller_manager/list_controller_types' "
                             "to get the available types")
        self.assertFalse(self.cm.load('no_type'))
        self.rosout.wait_for("Could not load controller 'no_type' because the type was not specified. Did you load "
                             "the controller configuration on the parameter server (namespace: '/no_type')?")
        self.assertFalse(self.cm.load('not_configured_at_all'))
        self.assertFalse(self.cm.load('failing'))
        self.rosout.wait_for("Initializing controller 'failing' failed")
        self.assertFalse(self.cm.load('imu'))
        self.rosout.wait_for("This controller requires a hardware interface of type "
                             "'hardware_interface::ImuSensorInterface'")
        self.assertEqual({}, self.cm.states())

    def test_load_list_unload(self):
        self.assertTrue(self.cm.load('effort_j1'))
        self.assertFalse(self.cm.load('effort_j1'))
        self.rosout.wait_for("A controller named 'effort_j1' was already loaded inside the controller manager")
        c = self.cm.controllers()['effort_j1']
        self.assertEqual('initialized', c.state)
        self.assertEqual('controller_manager_tests/EffortTestController', c.type)
        self.assertEqual(1, len(c.claimed_resources))
        self.assertEqual('hardware_interface::EffortJointInterface', c.claimed_resources[0].hardware_interface)
        self.assertEqual(['joint1'], c.claimed_resources[0].resources)
        self.assertTrue(self.cm.unload('effort_j1'))
        self.assertFalse(self.cm.unload('effort_j1'))
        self.rosout.wait_for("Could not unload controller with name effort_j1 "
                             "because no controller with this name exists")

    def test_switch_strict_and_best_effort(self):
        self.assertTrue(self.cm.load('velocity_j2'))
        self.assertFalse(self.cm.switch(start=['velocity_j2', 'nope'], strictness=STRICT))
        self.rosout.wait_for("Could not start controller with name nope because no controller with this name exists")
        self.assertEqual({'velocity_j2': 'initialized'}, self.cm.states())
        self.assertTrue(self.cm.switch(start=['velocity_j2', 'nope'], strictness=BEST_EFFORT))
        self.assertEqual({'velocity_j2': 'running'}, self.cm.states())
        # the controller really runs: joint2's command is its velocity
        self.commands.wait(lambda d: abs(d[1] - 0.5) < 1e-9)
        self.assertFalse(self.cm.switch(start=['velocity_j2'], strictness=STRICT))
        self.rosout.wait_for("Controller 'velocity_j2' is already running")
        self.assertTrue(self.cm.switch(stop=['velocity_j2']))
        self.assertEqual({'velocity_j2': 'stopped'}, self.cm.states())
        self.commands.wait(lambda d: d[1] == 0.0)  # the dummy zeroes the command of a released joint

    def test_unload_running_refused(self):
        self.assertTrue(self.cm.load('state'))
        self.assertTrue(self.cm.switch(start=['state']))
        self.assertFalse(self.cm.unload('state'))
        self.rosout.wait_for("Could not unload controller with name state because it is still running")
        self.assertEqual({'state': 'running'}, self.cm.states())

    def test_two_controllers_on_one_joint_refused(self):
        self.assertTrue(self.cm.load('effort_j1'))
        self.assertTrue(self.cm.load('velocity_j1'))
        self.assertFalse(self.cm.switch(start=['effort_j1', 'velocity_j1']))
        self.rosout.wait_for("Resource conflict on [joint1].  Controllers = [effort_j1, velocity_j1, ]")
        self.rosout.wait_for("Could not switch controllers, due to resource conflict")
        self.assertEqual({'effort_j1': 'initialized', 'velocity_j1': 'initialized'}, self.cm.states())
        self.assertTrue(self.cm.switch(start=['effort_j1']))
        self.assertFalse(self.cm.switch(start=['velocity_j1'], strictness=BEST_EFFORT))
        self.assertTrue(self.cm.switch(start=['velocity_j1'], stop=['effort_j1']))
        self.assertEqual({'effort_j1': 'stopped', 'velocity_j1': 'running'}, self.cm.states())

    def test_plugin_exported_with_class_list_macros_h(self):
        # libcontroller_manager_tests_compat includes the ROS 1 header name (package pluginlib_compat)
        self.assertTrue(self.cm.load('compat'))
        c = self.cm.controllers()['compat']
        self.assertEqual('controller_manager_tests/CompatTestController', c.type)
        self.assertEqual('initialized', c.state)
        self.assertTrue(self.cm.switch(start=['compat']))
        self.assertEqual({'compat': 'running'}, self.cm.states())
        self.assertTrue(self.cm.switch(stop=['compat']))
        self.assertEqual({'compat': 'stopped'}, self.cm.states())
        self.assertTrue(self.cm.unload('compat'))
        self.assertEqual({}, self.cm.states())

    def test_reload_libraries(self):
        self.assertTrue(self.cm.load('state'))
        self.assertTrue(self.cm.switch(start=['state']))
        self.assertFalse(self.cm.reload_srv(False).ok)
        self.rosout.wait_for("Cannot reload controller libraries because there are still 1 controllers running")
        self.assertTrue(self.cm.reload_srv(True).ok)
        self.assertEqual({}, self.cm.states())
        self.assertTrue(self.cm.load('state'))  # plugins can be loaded again


if __name__ == '__main__':
    rostest.rosrun('controller_manager_tests', 'check_services', ServicesTest)
