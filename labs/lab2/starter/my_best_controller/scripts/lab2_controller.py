#!/usr/bin/env python3
"""Lab 2 controller skeleton. Use only relative ('turtle1/pose') or private ('~x') names."""
import rospy
from geometry_msgs.msg import Twist
from turtlesim.msg import Pose

pose = None


def on_pose(msg):
    global pose
    pose = msg


if __name__ == '__main__':
    rospy.init_node('lab2_controller')
    ns = rospy.get_namespace()          # '/ns1_<ISU>/' or '/ns2_<ISU>/'
    rospy.Subscriber('turtle1/pose', Pose, on_pose)
    cmd = rospy.Publisher('turtle1/cmd_vel', Twist, queue_size=1)
    rate = rospy.Rate(50)
    while not rospy.is_shutdown():
        twist = Twist()
        # TODO ns1: drive through your variant's points, then publish the elapsed time
        #           (std_msgs/Float64) on 'result_<ISU>'.
        # TODO ns2: subscribe to turtle 1's pose and repeat its path.
        cmd.publish(twist)
        rate.sleep()
