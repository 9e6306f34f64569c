#!/usr/bin/python3
"""A dynamic_reconfigure server of dynamic_reconfigure's own TestConfig, node /reconf_test."""
import rospy
from dynamic_reconfigure.cfg import TestConfig
from dynamic_reconfigure.server import Server

rospy.init_node('reconf_test')
Server(TestConfig, lambda config, level: config)
rospy.spin()
