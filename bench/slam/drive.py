#!/usr/bin/python3
"""bench/slam's driver: follows a fixed route through the office's rooms on ground truth
(/gazebo/model_states, model 'robot') with /diffbot_controller/cmd_vel, republishing the ground
truth pose at 20 Hz of sim time on /bench/ground_truth (geometry_msgs/PoseStamped) for the bag.
Exits when the route is done or after --seconds of sim time."""
import argparse
import math
import sys
import threading

import rospy
from gazebo_msgs.msg import ModelStates
from geometry_msgs.msg import PoseStamped, Twist

from course_runtime.geometry import yaw_of

# room B -> A -> B -> C -> B -> corridor -> store room D -> corridor -> B (doors: x=-2 / x=2 at
# y=-1.5, y=2 at x=-4, 0, 2.8; store room door x=3.5 at y=3)
ROUTE = [(0.0, -1.5), (-1.2, -1.5), (-3.0, -1.5), (-4.0, -0.8), (-4.0, 0.8), (-3.0, 0.2), (-3.0, -1.5),
         (-1.0, -1.5), (1.0, -1.5), (3.0, -1.5), (4.2, -0.8), (4.2, 0.8), (3.0, 0.2), (3.0, -1.5),
         (1.0, -1.5), (0.0, -0.6), (0.0, 1.0), (0.0, 3.0), (-3.0, 3.0), (-1.0, 3.0), (2.8, 3.0),
         (4.6, 3.0), (2.8, 3.0), (0.0, 3.0), (0.0, 1.0), (0.0, 0.0)]
SPEED = 0.25        # m/s
TURN = 0.8          # rad/s max


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--seconds', type=float, default=180.0)
    args = ap.parse_args(rospy.myargv(sys.argv)[1:])
    rospy.init_node('bench_slam_driver')
    lock = threading.Lock()
    state = {}
    gt_pub = rospy.Publisher('/bench/ground_truth', PoseStamped, queue_size=10)

    def on_states(msg):
        if 'robot' in msg.name:
            with lock:
                state['pose'] = msg.pose[msg.name.index('robot')]

    rospy.Subscriber('/gazebo/model_states', ModelStates, on_states, queue_size=1)
    cmd_pub = rospy.Publisher('/diffbot_controller/cmd_vel', Twist, queue_size=1)
    while not rospy.is_shutdown() and ('pose' not in state or cmd_pub.get_num_connections() == 0
                                       or state['pose'].position.z > 0.05):
        rospy.sleep(0.1)
    rospy.sleep(2.0)                   # settle on the wheels
    t0 = rospy.Time.now().to_sec()
    k = 0
    rate = rospy.Rate(20)
    while not rospy.is_shutdown() and k < len(ROUTE) and rospy.Time.now().to_sec() - t0 < args.seconds:
        with lock:
            pose = state['pose']
        ps = PoseStamped()
        ps.header.stamp, ps.header.frame_id, ps.pose = rospy.Time.now(), 'world', pose
        gt_pub.publish(ps)
        x, y, th = pose.position.x, pose.position.y, yaw_of(pose.orientation)
        gx, gy = ROUTE[k]
        dist = math.hypot(gx - x, gy - y)
        if dist < 0.12:
            k += 1
            continue
        err = math.atan2(math.sin(math.atan2(gy - y, gx - x) - th), math.cos(math.atan2(gy - y, gx - x) - th))
        cmd = Twist()
        cmd.angular.z = max(-TURN, min(TURN, 2.0 * err))
        cmd.linear.x = SPEED * max(0.0, math.cos(err)) ** 4 if abs(err) < 0.6 else 0.0
        cmd_pub.publish(cmd)
        try:
            rate.sleep()
        except rospy.ROSInterruptException:
            break
    cmd_pub.publish(Twist())
    rospy.loginfo('bench_slam_driver: %d of %d waypoints in %.1f s of sim time', k, len(ROUTE),
                  rospy.Time.now().to_sec() - t0)


if __name__ == '__main__':
    main()
