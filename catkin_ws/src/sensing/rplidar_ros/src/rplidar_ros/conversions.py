"""The one place where ROS messages meet the scan layout."""
from sensor_msgs.msg import LaserScan


def laser_scan(data, stamp, frame_id):
    msg = LaserScan()
    msg.header.stamp = stamp
    msg.header.frame_id = frame_id
    msg.angle_min = data.angle_min
    msg.angle_max = data.angle_max
    msg.angle_increment = data.angle_increment
    msg.scan_time = data.scan_time
    msg.time_increment = data.time_increment
    msg.range_min = data.range_min
    msg.range_max = data.range_max
    msg.ranges = data.ranges
    msg.intensities = data.intensities
    return msg
