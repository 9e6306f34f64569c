#!/usr/bin/python3
"""rostest checker of lab 1: observe the student's three nodes, write a per-criterion report."""
import sys
import unittest

import rospkg
import rospy
import rostest

from grading import lab1
from grading.common import write_report
from grading.observe import Lab1Observer


class Lab1Check(unittest.TestCase):
    crits = {}

    @classmethod
    def setUpClass(cls):
        rospy.init_node('lab1_checker')
        isu = str(rospy.get_param('~isu'))
        report = rospy.get_param('~report')
        workdir = rospy.get_param('~workdir', '/tmp')
        pkg_dir = rospkg.RosPack().get_path(lab1.PACKAGE)
        obs = Lab1Observer(isu, lab1.node_scripts(pkg_dir), workdir).run()
        crits = lab1.evaluate(obs)
        write_report(report, crits)
        cls.crits = {c.id: c for c in crits}


def _make(cid, en):
    def test(self):
        c = self.crits[cid]
        self.assertTrue(c.passed, c.reason['en'])
    test.__name__ = 'test_%s' % cid
    test.__doc__ = en
    return test


for _cid, _ru, _en in lab1.CRITERIA:
    setattr(Lab1Check, 'test_%s' % _cid, _make(_cid, _en))

if __name__ == '__main__':
    rostest.rosrun('lab1_grader', 'check_lab1', Lab1Check, sys.argv)
