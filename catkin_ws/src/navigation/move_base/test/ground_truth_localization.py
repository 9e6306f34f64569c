#!/usr/bin/python3
"""Test and bench stand-in for AMCL: publishes map -> odom so that map -> base_footprint is the
simulator's ground truth (/gazebo/get_model_state of model `robot`, 20 Hz) combined with
odom -> base_footprint at the simulator's stamp of that pose, future-dated by
~transform_tolerance (0.1 s) as AMCL does. Stamped from the sim time at which it is sent, not
from the odometry's stamp it was computed with: a busy machine delaying this node must not
make map -> odom look older than it is to the costmaps (whose pose lookups refuse a chain older
than their transform_tolerance). The space scanner is skid-steered: its wheel odometry
misjudges turns, so identity map -> odom would not do."""
import math
import rospy
import tf2_ros
from gazebo_msgs.srv import GetModelState
from geometry_msgs.msg import TransformStamped

from course_runtime.geometry import yaw_of


def main():
    rospy.init_node('ground_truth_localization')
    model = rospy.get_param('~model', 'robot')
    odom_frame = rospy.get_param('~odom_frame_id', 'odom')
    base_frame = rospy.get_param('~base_frame_id', 'base_footprint')
    global_frame = rospy.get_param('~global_frame_id', 'map')
    tol = rospy.Duration(rospy.get_param('~transform_tolerance', 0.1))
    buf = tf2_ros.Buffer(rospy.Duration(5.0))
    tf2_ros.TransformListener(buf)
    br = tf2_ros.TransformBroadcaster()
    rospy.wait_for_service('/gazebo/get_model_state')
    get_state = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState, persistent=True)
    rate = rospy.Rate(20.0)
    last_stamp = None
    while not rospy.is_shutdown():
        try:
            rate.sleep()
        except rospy.ROSInterruptException:
            break
        try:
            st = get_state(model, '')
        except rospy.ServiceException:
            get_state = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState,
                                           persistent=True)
            continue
        if not st.success:
            continue
        # odom -> base at the simulator's time of that pose (the response's stamp), so that
        # map -> odom carries no motion between the two readings (the latest odom -> base
        # instead was up to tens of ms older under load: centimetres at 0.4 m/s)
        try:
            t = buf.lookup_transform(odom_frame, base_frame, st.header.stamp,
                                     rospy.Duration(0.2))
        except (tf2_ros.LookupException, tf2_ros.ConnectivityException,
                tf2_ros.ExtrapolationException):
            try:
                t = buf.lookup_transform(odom_frame, base_frame, rospy.Time(0))
            except (tf2_ros.LookupException, tf2_ros.ConnectivityException,
                    tf2_ros.ExtrapolationException):
                continue
        p = st.pose
        gt = (p.position.x, p.position.y, yaw_of(p.orientation))
        ox, oy = t.transform.translation.x, t.transform.translation.y
        oyaw = yaw_of(t.transform.rotation)
        # map->odom = gt * inverse(odom->base)
        yaw = gt[2] - oyaw
        c, s = math.cos(yaw), math.sin(yaw)
        tx = gt[0] - (c * ox - s * oy)
        ty = gt[1] - (s * ox + c * oy)
        out = TransformStamped()
        out.header.stamp = max(t.header.stamp, rospy.Time.now()) + tol
        if last_stamp is not None and out.header.stamp <= last_stamp:
            continue
        last_stamp = out.header.stamp
        out.header.frame_id = global_frame
        out.child_frame_id = odom_frame
        out.transform.translation.x = tx
        out.transform.translation.y = ty
        out.transform.rotation.z = math.sin(yaw / 2)
        out.transform.rotation.w = math.cos(yaw / 2)
        br.sendTransform(out)


if __name__ == '__main__':
    main()
