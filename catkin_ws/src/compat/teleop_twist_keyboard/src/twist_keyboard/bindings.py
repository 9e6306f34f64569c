"""Key maps, help text and the command state of teleop_twist_keyboard 1.0.0 (no ROS imports)."""

HELP = """
Reading from the keyboard  and Publishing to Twist!
---------------------------
Moving around:
   u    i    o
   j    k    l
   m    ,    .

For Holonomic mode (strafing), hold down the shift key:
---------------------------
   U    I    O
   J    K    L
   M    <    >

t : up (+z)
b : down (-z)

anything else : stop

q/z : increase/decrease max speeds by 10%
w/x : increase/decrease only linear speed by 10%
e/c : increase/decrease only angular speed by 10%

CTRL-C to quit
"""

# key -> (x, y, z, th): direction of linear x/y/z and of the rotation about z
MOVE_BINDINGS = {
    'i': (1, 0, 0, 0),
    'o': (1, 0, 0, -1),
    'j': (0, 0, 0, 1),
    'l': (0, 0, 0, -1),
    'u': (1, 0, 0, 1),
    ',': (-1, 0, 0, 0),
    '.': (-1, 0, 0, 1),
    'm': (-1, 0, 0, -1),
    'O': (1, -1, 0, 0),
    'I': (1, 0, 0, 0),
    'J': (0, 1, 0, 0),
    'L': (0, -1, 0, 0),
    'U': (1, 1, 0, 0),
    '<': (-1, 0, 0, 0),
    '>': (-1, -1, 0, 0),
    'M': (-1, 1, 0, 0),
    't': (0, 0, 1, 0),
    'b': (0, 0, -1, 0),
}

# key -> (factor on speed, factor on turn)
SPEED_BINDINGS = {
    'q': (1.1, 1.1),
    'z': (0.9, 0.9),
    'w': (1.1, 1.0),
    'x': (0.9, 1.0),
    'e': (1.0, 1.1),
    'c': (1.0, 0.9),
}

CTRL_C = '\x03'
TIMEOUT = ''          # what the key reader returns when no key came within key_timeout
HELP_EVERY = 15       # the help text is printed again every 15th speed change


def vels(speed, turn):
    """The status line printed after every speed change."""
    return 'currently:\tspeed %s\tturn %s ' % (speed, turn)


class TeleopState:
    """Direction (x, y, z, th) and scale (speed [m/s], turn [rad/s]) driven by key presses.

    handle(key) returns (publish, messages): whether the command must be sent, and the lines to
    print. `quit` becomes True on Ctrl-C.
    """

    def __init__(self, speed=0.5, turn=1.0):
        self.speed = speed
        self.turn = turn
        self.x = self.y = self.z = self.th = 0
        self.status = 0
        self.quit = False

    def stopped(self):
        return self.x == 0 and self.y == 0 and self.z == 0 and self.th == 0

    def handle(self, key):
        messages = []
        if key in MOVE_BINDINGS:
            self.x, self.y, self.z, self.th = MOVE_BINDINGS[key]
        elif key in SPEED_BINDINGS:
            fs, ft = SPEED_BINDINGS[key]
            self.speed *= fs
            self.turn *= ft
            messages.append(vels(self.speed, self.turn))
            if self.status == HELP_EVERY - 1:
                messages.append(HELP)
            self.status = (self.status + 1) % HELP_EVERY
        else:
            # a key timeout while already stopped sends nothing
            if key == TIMEOUT and self.stopped():
                return False, messages
            self.x = self.y = self.z = self.th = 0
            if key == CTRL_C:
                self.quit = True
                return False, messages
        return True, messages

    def command(self):
        """(linear x, y, z, angular z) of the Twist to publish."""
        return (self.x * self.speed, self.y * self.speed, self.z * self.speed, self.th * self.turn)
