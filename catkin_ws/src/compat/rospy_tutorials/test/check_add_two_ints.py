#!/usr/bin/python3
"""rostest: add_two_ints_server adds, and a client of the wrong type (BadTwoInts) is refused."""
import unittest

import rospy
import rostest
from rospy_tutorials.srv import AddTwoInts, AddTwoIntsRequest, BadTwoInts


class AddTwoIntsTest(unittest.TestCase):

    def setUp(self):
        rospy.wait_for_service('add_two_ints', timeout=30.0)

    def test_sums(self):
        proxy = rospy.ServiceProxy('add_two_ints', AddTwoInts)
        for a, b in ((3, 4), (-50000, 50000), (2 ** 40, 2 ** 40), (-7, -8)):
            self.assertEqual(proxy(a, b).sum, a + b)
            self.assertEqual(proxy.call(AddTwoIntsRequest(a, b)).sum, a + b)

    def test_wrong_type_refused(self):
        bad = rospy.ServiceProxy('add_two_ints', BadTwoInts)
        with self.assertRaises(rospy.ServiceException):
            bad(1, 2)


if __name__ == '__main__':
    rospy.init_node('check_add_two_ints')
    rostest.rosrun('rospy_tutorials', 'add_two_ints', AddTwoIntsTest)
