"""mimic: every Pose on input/pose becomes a Twist on output/cmd_vel."""


def twist_values(pose):
    """(linear.x, angular.z) copied from a turtlesim/Pose (speed is |v|, so reverse motion is
    mimicked as forward motion, as in the original)."""
    return pose.linear_velocity, pose.angular_velocity


def main():
    import rospy
    from geometry_msgs.msg import Twist
    from turtlesim.msg import Pose

    rospy.init_node('turtle_mimic')
    # like the original's NodeHandles "input" and "output": a remap of the namespace itself
    # (input:=turtlesim1/turtle1) moves every topic under it
    input_ns = rospy.resolve_name('input')
    output_ns = rospy.resolve_name('output')
    pub = rospy.Publisher(output_ns + '/cmd_vel', Twist, queue_size=1)

    def pose_callback(pose):
        twist = Twist()
        twist.linear.x, twist.angular.z = twist_values(pose)
        pub.publish(twist)

    rospy.Subscriber(input_ns + '/pose', Pose, pose_callback, queue_size=1)
    rospy.spin()
    return 0
