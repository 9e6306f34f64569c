"""ROS wiring of rplidarNode: parameters, the start-up sequence, the scan loop, services and
reconnection after the device vanished."""
import os
import sys
import threading
import time

import rospy
from sensor_msgs.msg import LaserScan
from std_srvs.srv import Empty, EmptyResponse

from . import protocol as P
from . import scan as S
from .conversions import laser_scan
from .driver import Driver, Timeout, Disconnected, open_serial

RECONNECT_PERIOD = 1.0      # s


class StartupError(Exception):
    """Logged with ROS_ERROR; the node exits with -1 as the original."""


class RplidarNode:
    def __init__(self):
        g = rospy.get_param
        self.channel_type = g('~channel_type', 'serial')
        self.port = g('~serial_port', '/dev/ttyUSB0')
        self.baudrate = int(g('~serial_baudrate', 115200))
        self.frame_id = g('~frame_id', 'laser_frame')
        self.inverted = bool(g('~inverted', False))
        self.angle_compensate = bool(g('~angle_compensate', False))
        self.initial_reset = bool(g('~initial_reset', False))
        self.scan_mode = str(g('~scan_mode', ''))
        self.scan_frequency = float(g('~scan_frequency', 10.0))
        if self.scan_frequency <= 0:
            rospy.logerr('Parameter scan_frequency must be > 0 (got %g); using 10.0.', self.scan_frequency)
            self.scan_frequency = 10.0
        self.pub = rospy.Publisher('scan', LaserScan, queue_size=1000)
        self.driver = None
        self.mode = None
        self.lock = threading.Lock()
        self.motor_on = True
        self.last_resyncs = 0
        rospy.loginfo('RPLIDAR running on ROS package rplidar_ros, SDK Version: 2.1.0 '
                      '(re-implementation)')

    # ---- start-up -----------------------------------------------------------------------------
    def connect(self, first):
        if self.channel_type != 'serial':
            raise StartupError('Error, channel_type %s is not supported by this re-implementation '
                               '(serial only).' % self.channel_type)
        try:
            fd = open_serial(self.port, self.baudrate)
        except OSError:
            raise StartupError('Error, cannot bind to the specified serial port %s.' % self.port)
        self.driver = Driver(fd)
        try:
            if self.initial_reset and first:
                self.driver.reset()
                time.sleep(2.0)
            info = self.driver.get_info()
        except Timeout:
            raise StartupError('Error, operation time out. RESULT_OPERATION_TIMEOUT! ')
        except (P.ProtocolError, Disconnected) as e:
            raise StartupError('Error, unexpected error, code: %x (%s)' % (0x80008000, e))
        self.print_info(info)
        self.check_health()
        return info

    def print_info(self, info):
        rospy.loginfo('RPLIDAR MODE:A%dM%d', info.model >> 4, info.model & 0xF)
        rospy.loginfo('RPLIDAR S/N: %s', ''.join('%02X' % b for b in info.serial))
        rospy.loginfo('Firmware Ver: %d.%02d', info.firmware_major, info.firmware_minor)
        rospy.loginfo('Hardware Rev: %d', info.hardware)

    def check_health(self):
        try:
            h = self.driver.get_health()
        except (Timeout, P.ProtocolError, Disconnected):
            raise StartupError('Error, cannot retrieve rplidar health code: %x' % 0x80008002)
        if h.status == P.HEALTH_OK:
            rospy.loginfo('RPLidar health status : OK.')
        elif h.status == P.HEALTH_WARNING:
            rospy.loginfo('RPLidar health status : Warning.')
        else:
            raise StartupError('Error, rplidar internal error detected. Please reboot the device '
                               'to retry.')

    def start(self, info):
        """Motor on, scan mode chosen, scan started; False if scanning could not start."""
        modes, typical = self.driver.scan_modes(info)
        self.driver.set_motor(True)
        if self.scan_mode:
            chosen = [m for m in modes if m.name == self.scan_mode]
            if not chosen:
                rospy.logerr("scan mode `%s' is not supported by lidar, supported modes:", self.scan_mode)
                for m in modes:
                    rospy.logerr('\t%s: max_distance: %.1f m, Point number: %.1fK', m.name,
                                 m.max_distance, 1000.0 / m.us_per_sample)
                rospy.logerr('Can not start scan: %08x!', 0x80008001)
                return False
            mode = chosen[0]
        else:
            mode = modes[typical]
        try:
            self.driver.start_scan(mode)
        except (Timeout, P.ProtocolError) as e:
            rospy.logerr('Can not start scan: %08x! (%s)', 0x80008002, e)
            return False
        self.mode = mode
        self.multiple = S.compensate_multiple(mode.us_per_sample, self.scan_frequency)
        rospy.loginfo('current scan mode: %s, sample rate: %d Khz, max_distance: %.1f m, scan '
                      'frequency:%.1f Hz, ', mode.name, int(1000 / mode.us_per_sample + 0.5),
                      mode.max_distance, self.scan_frequency)
        return True

    # ---- services -----------------------------------------------------------------------------
    def stop_motor(self, _req):
        with self.lock:
            if self.driver is None:
                return None
            rospy.loginfo('Stop motor')
            self.motor_on = False
            try:
                self.driver.set_motor(False)
                self.driver.stop()
            except Disconnected:
                pass
            self.mode = None
        return EmptyResponse()

    def start_motor(self, _req):
        with self.lock:
            if self.driver is None:
                rospy.loginfo('lost connection')
                return None
            rospy.loginfo('Start motor')
            self.motor_on = True
            try:
                info = self.driver.get_info()
                self.start(info)
            except (Timeout, P.ProtocolError, Disconnected):
                rospy.loginfo('lost connection')
        return EmptyResponse()

    # ---- main loop ----------------------------------------------------------------------------
    def publish(self, nodes, stamp, duration):
        data = S.build(nodes, duration, self.inverted, self.angle_compensate, self.multiple,
                       self.mode.max_distance)
        self.pub.publish(laser_scan(data, stamp, self.frame_id))

    def spin_once(self):
        with self.lock:
            if self.mode is None:
                return 0.1
            start = rospy.Time.now()
            t0 = time.monotonic()
            try:
                nodes = self.driver.grab_scan(2.0)
            except Timeout:
                self.timeouts += 1
                if not os.path.exists(self.port):
                    raise Disconnected('%s does not exist any more' % self.port)
                return 0.0
            self.timeouts = 0
            duration = time.monotonic() - t0
            self.publish(nodes, start, duration)
            resyncs = self.driver.resyncs
            if resyncs != self.last_resyncs:
                rospy.logwarn_throttle(5.0, 'rplidar: invalid data from %s, resynchronised (%d bytes '
                                       'skipped so far)' % (self.port, resyncs))
                self.last_resyncs = resyncs
        return 0.0

    def reconnect(self):
        while not rospy.is_shutdown():
            try:
                with self.lock:
                    info = self.connect(first=False)
                    if self.motor_on:
                        self.start(info)
                rospy.loginfo('RPLIDAR reconnected on %s', self.port)
                return
            except StartupError as e:
                rospy.logwarn_throttle(10.0, 'RPLIDAR on %s not available yet (%s); retrying every '
                                       '%.0f s' % (self.port, e, RECONNECT_PERIOD))
                if self.driver is not None:
                    self.driver.close()
                    self.driver = None
            time.sleep(RECONNECT_PERIOD)

    def run(self):
        try:
            info = self.connect(first=True)
        except StartupError as e:
            rospy.logerr(str(e))
            if self.driver is not None:
                self.driver.close()
            return -1
        rospy.Service('stop_motor', Empty, self.stop_motor)
        rospy.Service('start_motor', Empty, self.start_motor)
        self.timeouts = 0
        self.start(info)
        while not rospy.is_shutdown():
            try:
                pause = self.spin_once()
            except Disconnected as e:
                rospy.logerr('RPLIDAR on %s disconnected (%s); reconnecting...', self.port, e)
                with self.lock:
                    self.driver.close()
                    self.driver = None
                    self.last_resyncs = 0
                self.reconnect()
                continue
            if pause:
                time.sleep(pause)
        with self.lock:
            if self.driver is not None:
                try:
                    self.driver.set_motor(False)
                    self.driver.stop()
                except Disconnected:
                    pass
                self.driver.close()
        return 0


def main():
    rospy.init_node('rplidar_node')
    sys.exit(RplidarNode().run())
