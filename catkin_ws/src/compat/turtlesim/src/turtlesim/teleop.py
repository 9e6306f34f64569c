"""turtle_teleop_key: arrow keys (or capital A-D) -> one Twist on turtle1/cmd_vel per key press."""
import os
import select
import sys
import termios

KEY_UP, KEY_DOWN, KEY_RIGHT, KEY_LEFT = 0x41, 0x42, 0x43, 0x44   # final byte of ESC [ A..D
KEY_QUIT = ord('q')

#: final byte -> (linear factor, angular factor)
BINDINGS = {
    KEY_UP: (1.0, 0.0),
    KEY_DOWN: (-1.0, 0.0),
    KEY_LEFT: (0.0, 1.0),
    KEY_RIGHT: (0.0, -1.0),
}

BANNER = ("Reading from keyboard\n"
          "---------------------------\n"
          "Use arrow keys to move the turtle. 'q' to quit.")


def command_for(byte, l_scale, a_scale):
    """(linear.x, angular.z) for one input byte, or None when the byte is not a motion key."""
    factors = BINDINGS.get(byte)
    if factors is None:
        return None
    return factors[0] * l_scale, factors[1] * a_scale


class RawTerminal:
    """Context manager: terminal without ICANON/ECHO (Ctrl-C still works), restored on exit."""

    def __init__(self, fd):
        self.fd = fd
        self.saved = None

    def __enter__(self):
        self.saved = termios.tcgetattr(self.fd)
        raw = termios.tcgetattr(self.fd)
        raw[3] &= ~(termios.ICANON | termios.ECHO)
        raw[6][termios.VMIN] = 1
        raw[6][termios.VTIME] = 0
        termios.tcsetattr(self.fd, termios.TCSANOW, raw)
        return self

    def __exit__(self, *exc):
        termios.tcsetattr(self.fd, termios.TCSANOW, self.saved)


def main():
    import rospy
    from geometry_msgs.msg import Twist

    fd = sys.stdin.fileno()
    if not os.isatty(fd):
        print('turtle_teleop_key: standard input is not a terminal; run it in a terminal window',
              file=sys.stderr)
        return 1
    rospy.init_node('teleop_turtle')
    l_scale = float(rospy.get_param('scale_linear', 2.0))
    a_scale = float(rospy.get_param('scale_angular', 2.0))
    pub = rospy.Publisher('turtle1/cmd_vel', Twist, queue_size=1)
    print(BANNER, flush=True)
    try:
        with RawTerminal(fd):
            while not rospy.is_shutdown():
                ready, _, _ = select.select([fd], [], [], 0.1)
                if not ready:
                    continue
                data = os.read(fd, 1)
                if not data:                      # EOF: the terminal went away
                    break
                byte = data[0]
                rospy.logdebug('value: 0x%02X', byte)
                if byte == KEY_QUIT:
                    rospy.logdebug('quit')
                    break
                cmd = command_for(byte, l_scale, a_scale)
                if cmd is None:
                    continue
                twist = Twist()
                twist.linear.x, twist.angular.z = cmd
                pub.publish(twist)
    except KeyboardInterrupt:
        pass
    rospy.signal_shutdown('quit')
    return 0
