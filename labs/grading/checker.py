"""The rostest side of a lab grader: one unittest case per criterion of the lab.

The checker node observes the student's running system once (in setUpClass), evaluates every
criterion, writes the JSON report that `labs/grade` reads, and turns each criterion into a test
method so rostest's own XML has one testcase per criterion too.
"""
import os
import sys
import unittest

import rospkg
import rospy
import rostest

from grading.common import reason, write_report


def tampered(crits, why):
    """Every criterion fails with the reason `tampering: why`."""
    for c in crits:
        c.set(False, reason('tampering: ' + why, 'tampering: ' + why))
    return crits


def foreign_publishers(owners, obs):
    """owners: {topic: service only its rightful publisher provides}; the reason when a node
    that does not provide that service publishes the topic, else None."""
    pubs, srvs = obs.get('pubs', {}), obs.get('srvs', {})
    for topic, service in sorted(owners.items()):
        for node, topics in sorted(pubs.items()):
            if topic in topics and service not in srvs.get(node, ()):
                return ('%s publishes %s, which only the node providing %s may publish'
                        % (node, topic, service))
    return None


def run_checker(lab_pkg, rules, observe):
    """Run the checker node of a lab: `lab_pkg` is its package (grading.labN: PACKAGE, CRITERIA),
    `rules` its rules module (evaluate, optionally topic_owners); `observe(isu, pkg_dir,
    workdir)` returns the observation to evaluate."""
    lab = lab_pkg.__name__.split('.')[-1]

    class Check(unittest.TestCase):
        crits = {}

        @classmethod
        def setUpClass(cls):
            rospy.init_node('%s_checker' % lab)
            shutdown = []
            rospy.core.add_preshutdown_hook(shutdown.append)
            isu = str(rospy.get_param('~isu'))
            # labs/grade passes the report path in the environment (not readable over ROS)
            report = os.environ.get('GRADING_REPORT') or rospy.get_param('~report')
            workdir = rospy.get_param('~workdir', '/tmp')
            pkg_dir = rospkg.RosPack().get_path(lab_pkg.PACKAGE)
            obs = observe(isu, pkg_dir, workdir)
            crits = rules.evaluate(obs)
            why = None
            if shutdown or rospy.is_shutdown():
                why = ('the checker was shut down through the ROS API before it finished (%s)'
                       % (shutdown[0] if shutdown else 'no reason given'))
            elif hasattr(rules, 'topic_owners'):
                why = foreign_publishers(rules.topic_owners(isu), obs)
            if why:
                crits = tampered(crits, why)
            write_report(report, crits)
            cls.crits = {c.id: c for c in crits}

    def make(cid, en):
        def test(self):
            c = self.crits[cid]
            self.assertTrue(c.passed, c.reason['en'])
        test.__name__ = 'test_%s' % cid
        test.__doc__ = en
        return test

    for cid, _ru, en in lab_pkg.CRITERIA:
        setattr(Check, 'test_%s' % cid, make(cid, en))
    Check.__name__ = Check.__qualname__ = '%sCheck' % lab.capitalize()
    rostest.rosrun('%s_grader' % lab, 'check_%s' % lab, Check, sys.argv)
