#!/usr/bin/env python3
"""The smallest useful ROS node: it starts, says hello once a second and stops on Ctrl+C.

Run it (roscore must be running):  rosrun my_robot_controller my_first_node.py
"""
import rospy


def main():
    rospy.init_node('my_first_node')
    rospy.loginfo('Hello from my_robot_controller!')
    rate = rospy.Rate(1)  # 1 Hz
    count = 0
    while not rospy.is_shutdown():
        count += 1
        rospy.loginfo('my_first_node is alive, tick %d', count)
        rate.sleep()


if __name__ == '__main__':
    try:
        main()
    except rospy.ROSInterruptException:
        pass
