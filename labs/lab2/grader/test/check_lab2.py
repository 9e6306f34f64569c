#!/usr/bin/python3
"""rostest checker of lab 2: observe the student's launch file, write a per-criterion report."""
import sys
import unittest

import rospkg
import rospy
import rostest

from grading import lab2
from grading.common import write_report
from grading.observe import Lab2Observer


class Lab2Check(unittest.TestCase):
    crits = {}

    @classmethod
    def setUpClass(cls):
        rospy.init_node('lab2_checker')
        isu = str(rospy.get_param('~isu'))
        report = rospy.get_param('~report')
        workdir = rospy.get_param('~workdir', '/tmp')
        pkg_dir = rospkg.RosPack().get_path(lab2.PACKAGE)
        obs = Lab2Observer(isu, pkg_dir, workdir).run()
        crits = lab2.evaluate(obs)
        write_report(report, crits)
        cls.crits = {c.id: c for c in crits}


def _make(cid, en):
    def test(self):
        c = self.crits[cid]
        self.assertTrue(c.passed, c.reason['en'])
    test.__name__ = 'test_%s' % cid
    test.__doc__ = en
    return test


for _cid, _ru, _en in lab2.CRITERIA:
    setattr(Lab2Check, 'test_%s' % _cid, _make(_cid, _en))

if __name__ == '__main__':
    rostest.rosrun('lab2_grader', 'check_lab2', Lab2Check, sys.argv)
