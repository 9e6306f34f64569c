"""ROS wiring of the emulated RPLIDAR A1: parameters, the pty, the pacing loop."""
import select
import time

import rospy
from std_srvs.srv import Empty, EmptyResponse

from . import protocol as P
from .emulator import A1Device, PtyPort, Room, parse_pillars


def main():
    rospy.init_node('rplidar_emulator')
    g = rospy.get_param
    port = g('~port', '/tmp/ttyRPLIDAR')
    try:
        room = Room(float(g('~room_width', 6.0)), float(g('~room_length', 4.0)),
                    float(g('~x', 2.0)), float(g('~y', 1.5)), float(g('~yaw', 0.0)),
                    parse_pillars(g('~pillars', '4.0,3.0,0.3')))
    except ValueError as e:
        rospy.logfatal('rplidar_emulator: parameter ~pillars: %s', e)
        return 1
    if not (0 < room.x < room.width and 0 < room.y < room.length):
        rospy.logfatal('rplidar_emulator: the lidar (~x %.2f, ~y %.2f) must be inside the room '
                       '(~room_width %.2f, ~room_length %.2f)', room.x, room.y, room.width, room.length)
        return 1
    fw = str(g('~firmware', '1.20')).split('.')
    health = {'ok': P.HEALTH_OK, 'warning': P.HEALTH_WARNING, 'error': P.HEALTH_ERROR}.get(
        str(g('~health', 'ok')).lower())
    if health is None:
        rospy.logfatal("rplidar_emulator: parameter ~health must be 'ok', 'warning' or 'error'")
        return 1

    def make():
        return A1Device(room, float(g('~scan_frequency', 10.0)), (int(fw[0]), int(fw[1])),
                        health=health, garbage_every=float(g('~garbage_every', 0.0)))
    vanish_after = float(g('~vanish_after', 0.0))
    vanish_duration = float(g('~vanish_duration', 2.0))
    unplug = {'requested': False}

    def unplug_callback(_req):
        unplug['requested'] = True
        return EmptyResponse()
    rospy.Service('~unplug', Empty, unplug_callback)
    dev = make()
    pty = PtyPort(port)
    rospy.loginfo('rplidar_emulator: RPLIDAR A1M8 (firmware %s) on %s, room %.1f x %.1f m',
                  '.'.join(fw), port, room.width, room.length)
    t_start = time.monotonic()
    vanished = False
    try:
        while not rospy.is_shutdown():
            now = time.monotonic()
            if unplug['requested'] or (vanish_after > 0 and not vanished and
                                       now - t_start > vanish_after):
                unplug['requested'] = False
                rospy.logwarn('rplidar_emulator: unplugging %s for %.1f s', port, vanish_duration)
                pty.close()
                time.sleep(vanish_duration)
                dev = make()
                pty = PtyPort(port)
                vanished = True
                rospy.loginfo('rplidar_emulator: plugged in again on %s', port)
                continue
            r, _, _ = select.select([pty.master], [], [], 0.002)
            if r:
                data = pty.read()
                if data:
                    reply = dev.receive(data, now)
                    if reply:
                        pty.write(reply)
            out = dev.stream(time.monotonic())
            if out:
                pty.write(out)
    finally:
        pty.close()
    return 0
