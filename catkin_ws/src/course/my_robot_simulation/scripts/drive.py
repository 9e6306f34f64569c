#!/usr/bin/env python3
"""Drive the simulated robot by publishing geometry_msgs/Twist to cmd_vel
(self-study 2 of practical work 4).

    rosrun my_robot_simulation drive.py                     # a 1 m square, forever
    rosrun my_robot_simulation drive.py _pattern:=circle _speed:=0.3 _turn_rate:=0.6
    rosrun my_robot_simulation drive.py _duration:=5        # stop after 5 s (sim time)
    ROS_NAMESPACE=robot2 rosrun my_robot_simulation drive.py   # /robot2/cmd_vel

Parameters: ~pattern (forward|circle|square|spin|zigzag), ~speed (m/s), ~turn_rate (rad/s),
~side (m, square/zigzag), ~rate (Hz), ~duration (s, 0 = until Ctrl-C). Stops the robot
(a zero Twist) on exit: the diff-drive plugin keeps the last command forever.
"""
import sys
import time

import rospy
from geometry_msgs.msg import Twist

from my_robot_simulation.motion import MotionError, check, command


def main():
    rospy.init_node('drive')
    pattern = rospy.get_param('~pattern', 'square')
    speed = float(rospy.get_param('~speed', 0.2))
    turn_rate = float(rospy.get_param('~turn_rate', 0.5))
    side = float(rospy.get_param('~side', 1.0))
    rate_hz = float(rospy.get_param('~rate', 10.0))
    duration = float(rospy.get_param('~duration', 0.0))
    try:
        check(pattern, speed, turn_rate, side)
    except MotionError as e:
        rospy.logfatal('drive.py: %s', e)
        sys.exit(2)
    pub = rospy.Publisher('cmd_vel', Twist, queue_size=1)

    def stop():
        pub.publish(Twist())
    rospy.on_shutdown(stop)

    while not rospy.is_shutdown() and rospy.Time.now().is_zero():   # sim time not running yet
        rospy.sleep(0.05)
    start = rospy.Time.now()
    rospy.loginfo('drive.py: %s on %s (speed %.2f m/s, turn %.2f rad/s)',
                  pattern, pub.resolved_name, speed, turn_rate)
    rate = rospy.Rate(rate_hz)
    while not rospy.is_shutdown():
        t = (rospy.Time.now() - start).to_sec()
        if duration > 0 and t >= duration:
            break
        v, w = command(pattern, max(t, 0.0), speed, turn_rate, side)
        msg = Twist()
        msg.linear.x, msg.angular.z = v, w
        pub.publish(msg)
        try:
            rate.sleep()
        except rospy.ROSTimeMovedBackwardsException:
            start = rospy.Time.now()     # the simulation was reset
        except rospy.ROSInterruptException:
            break
    stop()
    time.sleep(0.2)     # wall time: let the last message go out even if the clock stopped


if __name__ == '__main__':
    main()
