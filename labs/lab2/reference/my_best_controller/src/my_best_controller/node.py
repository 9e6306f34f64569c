"""Lab 2 reference, ROS part: the role comes from the namespace (ns1_<ISU> or ns2_<ISU>)."""
import sys

import rospy
from geometry_msgs.msg import Twist
from std_msgs.msg import Float64
from turtlesim.msg import Pose

from my_best_controller.motion import Follower, Leader, POINTS, parse_namespace

RATE = 50.0   # Hz


def main():
    rospy.init_node('lab2_controller')
    ns = rospy.get_namespace()
    parsed = parse_namespace(ns)
    if parsed is None:
        rospy.logfatal('lab2_controller: run me in namespace ns1_<ISU> or ns2_<ISU>, not %s', ns)
        sys.exit(1)
    role, isu = parsed
    pose = {}
    rospy.Subscriber('turtle1/pose', Pose, lambda m: pose.update(p=(m.x, m.y, m.theta)), queue_size=1)
    cmd = rospy.Publisher('turtle1/cmd_vel', Twist, queue_size=1)
    if role == 1:
        brain = Leader(POINTS[int(isu[-1])])
        result = rospy.Publisher('result_%s' % isu, Float64, queue_size=1, latch=True)
    else:
        brain = Follower()
        leader_ns = ns.replace('ns2_', 'ns1_', 1)   # the twin namespace, from our own
        rospy.Subscriber(leader_ns + 'turtle1/pose', Pose, lambda m: brain.leader_at(m.x, m.y), queue_size=50)
    rospy.loginfo('lab2_controller: %s, ISU %s', 'leader' if role == 1 else 'follower', isu)
    rate = rospy.Rate(RATE)
    started = reported = None
    while not rospy.is_shutdown():
        if 'p' in pose:
            v, w = brain.command(*pose['p'])
            if role == 1:
                if started is None and (v or w):
                    started = rospy.get_time()
                if brain.done and reported is None:
                    reported = rospy.get_time() - started
                    result.publish(Float64(reported))
                    rospy.loginfo('lab2_controller: all points reached in %.2f s', reported)
            t = Twist()
            t.linear.x, t.angular.z = v, w
            cmd.publish(t)
        try:
            rate.sleep()
        except rospy.ROSInterruptException:
            break
