#!/usr/bin/python3
"""rostest node: every link of robot_description has a transform (see course_testing.tf_check)."""
from course_testing import tf_check

if __name__ == '__main__':
    tf_check.main('my_robot_model')
