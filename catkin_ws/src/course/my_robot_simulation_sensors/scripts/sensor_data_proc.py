#!/usr/bin/env python3
"""Camera and lidar data of the simulated robot (practical work 6).

Subscribes to the camera image (~image_topic, default /diff_drive_robot/camera1/image_raw, the
textbook's) and the lidar scan (~scan_topic, default /diff_drive_robot/laser). Each image is
converted with cv_bridge to an OpenCV BGR frame, its Canny edges (~low, ~high thresholds) are
published as sensor_msgs/Image mono8 on ~edges and, when a display is available (DISPLAY set and
~show true), both are shown with cv2.imshow. Image and scan statistics are logged once per
~log_period seconds.

    rosrun my_robot_simulation_sensors sensor_data_proc.py
    rosrun my_robot_simulation_sensors sensor_data_proc.py _image_topic:=/camera/image_raw   # another camera
"""
import os

import cv2
import rospy
from cv_bridge import CvBridge
from sensor_msgs.msg import Image, LaserScan

from my_robot_simulation_sensors import image_proc, scan_proc


class sensor_datahandler:
    def __init__(self):
        self.bridge = CvBridge()
        self.low = float(rospy.get_param('~low', 100))
        self.high = float(rospy.get_param('~high', 200))
        self.show = bool(rospy.get_param('~show', True)) and bool(os.environ.get('DISPLAY'))
        self.log_period = float(rospy.get_param('~log_period', 2.0))
        self.curent_image = None
        self.frames = 0
        self.edges_pub = rospy.Publisher('~edges', Image, queue_size=1)
        self.camera_subscriber = rospy.Subscriber(rospy.get_param('~image_topic',
                                                                  '/diff_drive_robot/camera1/image_raw'),
                                                  Image, self.camera_cb, queue_size=1, buff_size=2 ** 24)
        self.scan_subscriber = rospy.Subscriber(rospy.get_param('~scan_topic', '/diff_drive_robot/laser'),
                                                LaserScan, self.scan_cb, queue_size=1)

    def camera_cb(self, data):
        try:
            frame = image_proc.to_bgr(self.bridge, data)
            edges = image_proc.canny(frame, self.low, self.high)
        except image_proc.ImageError as e:
            rospy.logerr_throttle(5.0, 'sensor_data_proc: %s' % e)
            return
        self.curent_image = frame
        self.frames += 1
        out = self.bridge.cv2_to_imgmsg(edges, encoding='mono8')
        out.header = data.header
        self.edges_pub.publish(out)
        s = image_proc.stats(frame, edges)
        rospy.loginfo_throttle(self.log_period, 'image %dx%d (%d frames): mean %.0f, edges %.1f %%'
                               % (s['width'], s['height'], self.frames, s['mean'], 100 * s['edge_fraction']))
        if self.show:
            cv2.imshow('output', frame)
            cv2.imshow('edges', edges)
            cv2.waitKey(1)

    def scan_cb(self, scan):
        rospy.loginfo_throttle(self.log_period, 'scan: ' + scan_proc.describe(scan))


if __name__ == '__main__':
    rospy.init_node('camera_data_processing')
    sensor_datahandler()
    rospy.spin()
    cv2.destroyAllWindows()
