#!/usr/bin/env python3
"""rosrun rosserial_python serial_node.py [PORT|tcp [TCP_PORT]] [_port:=...] [_baud:=...]"""
import sys
import time

import rospy

from rosserial_python.SerialClient import RosSerialServer, SerialClient


def main():
    rospy.init_node('serial_node')
    rospy.loginfo('ROS Serial Python Node')
    argv = rospy.myargv(sys.argv)[1:]
    port_name = rospy.get_param('~port', '/dev/ttyUSB0')
    try:
        baud = int(rospy.get_param('~baud', 57600))
    except (TypeError, ValueError):
        rospy.logfatal('~baud: %r is not an integer baud rate' % rospy.get_param('~baud'))
        sys.exit(1)
    fix = bool(rospy.get_param('~fix_pyserial_for_test', False))
    tcp_port = int(rospy.get_param('/rosserial_embeddedlinux/tcp_port', 11411))
    fork_server = bool(rospy.get_param('/rosserial_embeddedlinux/fork_server', False))
    if argv:
        port_name = argv[0]
    if port_name == 'tcp':
        if len(argv) > 1:
            tcp_port = int(argv[1])
        rospy.loginfo('Fork_server is: %s' % fork_server)
        RosSerialServer(tcp_port, fork_server).listen()
        return
    import serial
    while not rospy.is_shutdown():
        rospy.loginfo('Connecting to %s at %d baud' % (port_name, baud))
        client = None
        try:
            client = SerialClient(port_name, baud, fix_pyserial_for_test=fix)
            client.run()
        except KeyboardInterrupt:
            break
        except (serial.SerialException, OSError) as e:
            if not rospy.is_shutdown():
                rospy.logwarn('Serial port problem (%s): reconnecting' % e)
            time.sleep(1.0)
        except Exception as e:
            rospy.logwarn('Unexpected Error: %s', e)
            time.sleep(1.0)
        finally:
            if client is not None:
                client.close()


if __name__ == '__main__':
    main()
