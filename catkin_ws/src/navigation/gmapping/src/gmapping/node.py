"""slam_gmapping's ROS wiring: parameters, scan subscription with TF lookups, map / map_metadata /
~entropy publishing, the dynamic_map service and the map->odom broadcaster."""
import threading

import numpy as np
import rospy
import tf2_ros
from nav_msgs.msg import MapMetaData
from sensor_msgs.msg import LaserScan
from std_msgs.msg import Float64

from gmapping import conversions
from gmapping.params import ParamError, SlamParams, validate
from gmapping.rbpf import GridSlam
from map_server.conversions import NumpyGetMap, NumpyGetMapResponse, NumpyOccupancyGrid

INT_PARAMS = ('particles', 'kernelSize', 'iterations', 'lskip', 'throttle_scans')
STR_PARAMS = ('base_frame', 'map_frame', 'odom_frame')
NO_SCAN_WARN = 5.0      # s without a scan before the watchdog warns
TF_WAIT = 1.0           # s (simulated when use_sim_time) a scan waits for its odometry transform,
# as the original's tf message filter holds scans until TF has caught up


def read_params():
    p = SlamParams()
    for name in SlamParams.names():
        if not rospy.has_param('~' + name):
            continue
        value = rospy.get_param('~' + name)
        try:
            if name in STR_PARAMS:
                value = str(value)
            elif name in INT_PARAMS:
                value = int(value)
            else:
                value = float(value)
        except (TypeError, ValueError):
            raise ParamError('~%s must be a %s (got %r)' % (
                name, 'string' if name in STR_PARAMS else 'number', value))
        setattr(p, name, value)
    if p.tf_delay < 0.0:
        p.tf_delay = p.transform_publish_period
    validate(p)
    return p


class SlamGMapping(object):
    """live=True: scans from the `scan` topic, odometry from the TF listener, map->odom
    broadcast every transform_publish_period. live=False (slam_gmapping_replay): the caller fills
    tf_buffer and hands scans to laser_callback(); map->odom goes out with each processed scan and
    the stamps come from the scans, so no clock is needed."""

    def __init__(self, params, live=True, seed=None, tf_cache=30.0):
        self.p = params
        self.live = live
        if seed is None:
            seed = rospy.get_param('~seed', None)
        self.slam = GridSlam(params, seed=seed)
        self.lock = threading.Lock()
        self.tf_buffer = tf2_ros.Buffer(rospy.Duration(tf_cache))
        self.tf_wait = rospy.Duration(TF_WAIT if live else 0.0)
        self.last_stamp = None
        if live:
            self.tf_listener = tf2_ros.TransformListener(self.tf_buffer)
        self.tf_broadcaster = tf2_ros.TransformBroadcaster()
        self.map_pub = rospy.Publisher('map', NumpyOccupancyGrid, queue_size=1, latch=True)
        self.meta_pub = rospy.Publisher('map_metadata', MapMetaData, queue_size=1, latch=True)
        self.entropy_pub = rospy.Publisher('~entropy', Float64, queue_size=1, latch=True)
        self.map_to_odom = np.zeros(3)
        self.map = None
        self.last_map_update = None
        self.scan_count = 0
        self.last_scan_time = None          # watchdog: "no scan for N s"
        self.start_time = rospy.get_time()
        self.beams = None
        self.upside_down = False
        self.max_range = self.max_urange = None
        rospy.Service('dynamic_map', NumpyGetMap, self.map_callback)
        if not live:
            return
        self.scan_sub = rospy.Subscriber('scan', LaserScan, self.laser_callback, queue_size=5)
        if params.transform_publish_period > 0.0:
            self.tf_thread = threading.Thread(target=self.publish_loop, daemon=True)
            self.tf_thread.start()

    def check_scans(self):
        """A throttled warning while no scan arrives (5 s of ROS time without one)."""
        now = rospy.get_time()
        last = self.last_scan_time if self.last_scan_time is not None else self.start_time
        if now - last > NO_SCAN_WARN:
            rospy.logwarn_throttle(NO_SCAN_WARN, 'slam_gmapping: no scan received for %.0f s on topic %s: check '
                                   'the laser driver and the remapping of "scan"'
                                   % (now - last, self.scan_sub.resolved_name))

    def publish_loop(self):
        rate = rospy.Rate(1.0 / self.p.transform_publish_period)
        last = None
        while not rospy.is_shutdown():
            self.check_scans()
            with self.lock:
                pose = self.map_to_odom.copy()
            stamp = rospy.Time.now() + rospy.Duration(self.p.tf_delay)
            # a loop that catches up after a jump of the simulated clock would send the same
            # stamp twice (tf2's TF_REPEATED_DATA warning in every listener): once per stamp
            if not stamp.is_zero() and stamp != last:
                last = stamp
                self.tf_broadcaster.sendTransform(
                    conversions.transform_msg(pose, self.p.map_frame, self.p.odom_frame, stamp))
            try:
                rate.sleep()
            except rospy.ROSInterruptException:
                break

    def map_callback(self, _req):
        with self.lock:
            if self.map is None:
                return None      # as the original: no map yet -> the call fails
            return NumpyGetMapResponse(map=self.map)

    def odom_laser_pose(self, scan):
        try:
            t = self.tf_buffer.lookup_transform(self.p.odom_frame, scan.header.frame_id, scan.header.stamp,
                                                self.tf_wait)
        except (tf2_ros.LookupException, tf2_ros.ConnectivityException, tf2_ros.ExtrapolationException) as e:
            rospy.logwarn_throttle(5.0, 'Failed to compute odom pose, skipping scan: no transform from '
                                   '"%s" (scan frame) to "%s" (odom_frame): %s'
                                   % (scan.header.frame_id, self.p.odom_frame, e))
            return None
        return t

    def init_laser(self, scan, t):
        upz = conversions.up_z(t.transform.rotation)
        if abs(abs(upz) - 1.0) > 0.001:
            rospy.logwarn_throttle(5.0, 'Laser has to be mounted planar! Z-coordinate has to be 1 or -1, but gave: '
                                   '%.5f (frame "%s" in "%s")' % (upz, scan.header.frame_id, self.p.odom_frame))
            return False
        self.upside_down = upz < 0
        if self.upside_down:
            rospy.loginfo('Laser is mounted upside down.')
        self.beams = len(scan.ranges)
        self.max_range = self.p.maxRange if self.p.maxRange > 0.0 else scan.range_max - 0.01
        self.max_urange = self.p.maxUrange if self.p.maxUrange > 0.0 else self.max_range
        rospy.loginfo('slam_gmapping: %d beams, maxRange %.2f m, maxUrange %.2f m, %d particles, delta %.3f m',
                      self.beams, self.max_range, self.max_urange, self.p.particles, self.p.delta)
        return True

    def laser_callback(self, scan):
        self.last_scan_time = rospy.get_time()
        self.scan_count += 1
        if self.scan_count % self.p.throttle_scans:
            return
        t = self.odom_laser_pose(scan)
        if t is None:
            return
        if self.beams is None and not self.init_laser(scan, t):
            return
        if len(scan.ranges) != self.beams:
            rospy.logwarn_throttle(5.0, 'slam_gmapping: scan with %d beams dropped (the first had %d)'
                                   % (len(scan.ranges), self.beams))
            return
        odom_pose = conversions.transform_to_pose(t.transform)
        ranges, angles = conversions.scan_beams(scan, self.upside_down)
        stamp = scan.header.stamp.to_sec()
        if not self.slam.process(odom_pose, ranges, angles, self.max_range, self.max_urange, stamp):
            return
        correction = conversions.map_to_odom(self.slam.best_pose(), odom_pose)
        with self.lock:
            self.map_to_odom = correction
        self.last_stamp = scan.header.stamp
        if not self.live:
            self.tf_broadcaster.sendTransform(conversions.transform_msg(
                correction, self.p.map_frame, self.p.odom_frame,
                scan.header.stamp + rospy.Duration(self.p.tf_delay)))
        self.entropy_pub.publish(Float64(self.slam.weight_entropy()))
        if self.last_map_update is None or stamp - self.last_map_update >= self.p.map_update_interval:
            self.update_map()
            self.last_map_update = stamp

    def update_map(self):
        grid, origin = self.slam.occupancy()
        stamp = rospy.Time.now() if self.live else self.last_stamp
        msg = conversions.map_msg(grid, origin, self.p, self.p.map_frame, stamp)
        with self.lock:
            self.map = msg
        self.meta_pub.publish(msg.info)
        self.map_pub.publish(msg)
        rospy.logdebug('slam_gmapping: map updated (%d scans processed)', self.slam.count)


def main():
    rospy.init_node('slam_gmapping')
    try:
        params = read_params()
    except ParamError as e:
        rospy.logerr('slam_gmapping: %s', e)
        return 1
    SlamGMapping(params)
    rospy.spin()
    return 0
