#!/usr/bin/python3
"""Drive a robot from the keyboard: publishes geometry_msgs/Twist on `cmd_vel`."""
import sys

import rospy
from geometry_msgs.msg import Twist

from twist_keyboard.bindings import HELP, TeleopState, vels
from twist_keyboard.publish_thread import PublishThread
from twist_keyboard.terminal import KeyReader, NotATerminal


def main():
    try:
        keys = KeyReader(sys.stdin.fileno())
    except NotATerminal as e:
        print('teleop_twist_keyboard: %s' % e, file=sys.stderr)
        return 1

    rospy.init_node('teleop_twist_keyboard')
    state = TeleopState(speed=float(rospy.get_param('~speed', 0.5)),
                        turn=float(rospy.get_param('~turn', 1.0)))
    repeat = float(rospy.get_param('~repeat_rate', 0.0))
    key_timeout = float(rospy.get_param('~key_timeout', 0.0))
    if repeat < 0.0 or key_timeout < 0.0:
        print('teleop_twist_keyboard: ~repeat_rate and ~key_timeout must be >= 0 (got %s, %s)'
              % (repeat, key_timeout), file=sys.stderr)
        return 1

    publisher = rospy.Publisher('cmd_vel', Twist, queue_size=1)
    pub_thread = PublishThread(publisher, repeat)
    # on SIGINT/roslaunch shutdown: send the zero twist while the publisher is still open
    rospy.on_shutdown(pub_thread.stop)
    try:
        if not pub_thread.wait_for_subscribers(rospy.is_shutdown, rospy.sleep,
                                               topic=publisher.resolved_name):
            return 0
        pub_thread.update(*state.command())
        print(HELP)
        print(vels(state.speed, state.turn))
        while not state.quit and not rospy.is_shutdown():
            key = keys.get_key(key_timeout or None, rospy.is_shutdown)
            if rospy.is_shutdown():
                break
            publish, messages = state.handle(key)
            for line in messages:
                print(line)
            if publish:
                pub_thread.update(*state.command())
    finally:
        pub_thread.stop()
        keys.restore()
    return 0


if __name__ == '__main__':
    sys.exit(main())
