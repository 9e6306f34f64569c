#!/usr/bin/python3
"""rostest node: every link of robot_description has a transform (see my_robot_model.tf_check)."""
from my_robot_model import tf_check

if __name__ == '__main__':
    tf_check.main('firstbot_description')
