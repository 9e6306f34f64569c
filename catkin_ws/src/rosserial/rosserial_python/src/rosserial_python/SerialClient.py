"""rosserial_python's public classes under the original's module name:
SerialClient (one device on a serial port or an accepted socket) and RosSerialServer (tcp mode).
"""
import socket
import time

import rospy

from .link import DeviceLink
from .ports import SerialPort, SocketPort
from .ros_backend import RosBackend


class SerialClient(object):
    """Open `port` (a path, retried every 3 s while it cannot be opened; or a port object with
    read_some/write/flush_input), wait for the board's reset, negotiate; run() bridges until
    shutdown and lets port errors propagate so the caller can reconnect."""

    def __init__(self, port=None, baud=57600, timeout=5.0, fix_pyserial_for_test=False,
                 reset_wait=2.0):
        self.backend = RosBackend()
        self.port = None
        if hasattr(port, 'read_some'):
            self.port = port
        else:
            import serial
            while not rospy.is_shutdown():
                try:
                    self.port = SerialPort(port, baud, fix_pyserial_for_test)
                    break
                except (serial.SerialException, OSError, ValueError) as e:
                    rospy.logerr('Error opening serial: %s', e)
                    time.sleep(3)
        if self.port is None:
            return
        time.sleep(0.1)
        if reset_wait:
            rospy.sleep(reset_wait)  # the board's DTR auto-reset and bootloader
        self.link = DeviceLink(self.port, self.backend, timeout=timeout,
                               flush=not fix_pyserial_for_test)
        rospy.on_shutdown(self.tx_stop)

    def tx_stop(self):
        try:
            self.link.tx_stop()
        except Exception:
            pass

    def run(self):
        if self.port is None:
            return
        self.link.run(rospy.is_shutdown)

    def close(self):
        if self.port is not None:
            try:
                self.port.close()
            except Exception:
                pass


class RosSerialServer(object):
    """tcp mode: accept rosserial clients on `tcp_portnum`, one at a time, each bridged like a
    serial device."""

    def __init__(self, tcp_portnum, fork_server=False):
        self.tcp_portnum = tcp_portnum
        self.fork_server = fork_server
        if fork_server:
            rospy.logwarn('fork_server is not supported: clients are served one at a time')

    def listen(self):
        server = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        server.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        server.bind(('', self.tcp_portnum))
        server.listen(1)
        server.settimeout(0.5)
        rospy.loginfo('Waiting for socket connections on port %d', self.tcp_portnum)
        try:
            while not rospy.is_shutdown():
                try:
                    sock, address = server.accept()
                except socket.timeout:
                    continue
                rospy.loginfo('Established a socket connection from %s on port %s' % address)
                client = SerialClient(SocketPort(sock), reset_wait=0)
                try:
                    client.run()
                except OSError as e:
                    rospy.loginfo('socket connection closed: %s', e)
                finally:
                    client.close()
                    for sub in client.link.subscribers.values():
                        sub.unregister()
        finally:
            server.close()
