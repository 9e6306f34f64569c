"""The rostest side of a lab grader: one unittest case per criterion of the lab.

The checker node observes the student's running system once (in setUpClass), evaluates every
criterion, writes the JSON report that `labs/grade` reads, and turns each criterion into a test
method so rostest's own XML has one testcase per criterion too.
"""
import sys
import unittest

import rospkg
import rospy
import rostest

from grading.common import write_report


def run_checker(lab, module, observe):
    """Run the checker node of `lab` ('lab1', 'lab2', 'lab3'): `module` is grading.labN (PACKAGE,
    CRITERIA, evaluate); `observe(isu, pkg_dir, workdir)` returns the observation to evaluate."""

    class Check(unittest.TestCase):
        crits = {}

        @classmethod
        def setUpClass(cls):
            rospy.init_node('%s_checker' % lab)
            isu = str(rospy.get_param('~isu'))
            report = rospy.get_param('~report')
            workdir = rospy.get_param('~workdir', '/tmp')
            pkg_dir = rospkg.RosPack().get_path(module.PACKAGE)
            crits = module.evaluate(observe(isu, pkg_dir, workdir))
            write_report(report, crits)
            cls.crits = {c.id: c for c in crits}

    def make(cid, en):
        def test(self):
            c = self.crits[cid]
            self.assertTrue(c.passed, c.reason['en'])
        test.__name__ = 'test_%s' % cid
        test.__doc__ = en
        return test

    for cid, _ru, en in module.CRITERIA:
        setattr(Check, 'test_%s' % cid, make(cid, en))
    Check.__name__ = Check.__qualname__ = '%sCheck' % lab.capitalize()
    rostest.rosrun('%s_grader' % lab, 'check_%s' % lab, Check, sys.argv)
