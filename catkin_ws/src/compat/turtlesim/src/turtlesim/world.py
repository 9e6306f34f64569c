"""The turtle world without ROS or Qt: kinematics, walls, pen, teleports, spawn naming.

Units: positions in metres in the world frame (origin lower-left, y up), angles in radians,
velocities in m/s and rad/s, the tick in seconds. Drawing goes through a `canvas` object with
`fill(rgb)`, `draw_line((x0, y0), (x1, y1), pen)` and `pixel((x, y)) -> (r, g, b)` in world
metres (see canvas.py); tests may pass any object with that interface.
"""
import math

WINDOW_PX = 500                          #: window width and height, pixels
METER_PX = 45.0                          #: pixels per metre (height of the turtle sprite)
WORLD_SIZE = (WINDOW_PX - 1) / METER_PX  #: 11.088889 m, width and height of the world
CENTRE = WORLD_SIZE / 2.0                #: where turtle1 starts, m
TICK = 0.016                             #: fixed integration step and timer period, s
CMD_TIMEOUT = 1.0                        #: wall time without cmd_vel after which the turtle stops, s
DEFAULT_BACKGROUND = (69, 86, 255)
DEFAULT_PEN = (179, 184, 255)
DEFAULT_PEN_WIDTH = 3
QT_DEFAULT_PEN_WIDTH = 1                 #: what SetPen width 0 gives (the width is not kept)


class TurtleError(Exception):
    """A request the world refuses (duplicate or unknown name); the message is the log line."""


def wrap_angle(theta):
    """Wrap an angle to [-pi, pi)."""
    return theta - 2.0 * math.pi * math.floor((theta + math.pi) / (2.0 * math.pi))


class Pen:
    def __init__(self, rgb=DEFAULT_PEN, width=DEFAULT_PEN_WIDTH):
        self.rgb = tuple(rgb)
        self.width = width

    def __repr__(self):
        return 'Pen(%r, %r)' % (self.rgb, self.width)


class Turtle:
    """One turtle: pose, the last velocity command and its pen."""

    def __init__(self, name, x, y, theta, sprite=0):
        self.name = name
        self.x, self.y, self.theta = float(x), float(y), float(theta)
        self.vx = self.vy = self.wz = 0.0
        self.last_command = None          # wall time of the last cmd_vel, s (None: never)
        self.pen = Pen()
        self.pen_on = True
        self.sprite = sprite
        self._teleports = []              # queued ('abs', x, y, theta) / ('rel', linear, angular)

    # --- requests (from callbacks; the world's lock is held by the caller) -------------------
    def command(self, vx, vy, wz, now):
        """A cmd_vel: body-frame velocities; `now` is wall time in seconds."""
        self.vx, self.vy, self.wz = float(vx), float(vy), float(wz)
        self.last_command = now

    def set_pen(self, r, g, b, width, off):
        """SetPen semantics: off != 0 only disables the pen (the old pen is kept); otherwise a
        new pen of colour r, g, b and `width` pixels (0 = Qt's default width 1)."""
        if off:
            self.pen_on = False
            return
        self.pen_on = True
        self.pen = Pen((r, g, b), width if width else QT_DEFAULT_PEN_WIDTH)

    def teleport_absolute(self, x, y, theta):
        self._teleports.append(('abs', float(x), float(y), float(theta)))

    def teleport_relative(self, linear, angular):
        self._teleports.append(('rel', float(linear), float(angular)))

    # --- the tick ---------------------------------------------------------------------------
    @property
    def linear_velocity(self):
        """|commanded velocity| as Pose reports it (always >= 0)."""
        return math.hypot(self.vx, self.vy)

    def step(self, dt, now, canvas, size=WORLD_SIZE):
        """Apply queued teleports, integrate one tick, clamp to the walls, draw the trail.

        Returns the wall-hit position in window coordinates (x, y from the top, metres) when the
        turtle was clamped, else None.
        """
        for req in self._teleports:
            old = (self.x, self.y)
            if req[0] == 'rel':
                self.theta += req[2]
                self.x += math.cos(self.theta) * req[1]
                self.y += math.sin(self.theta) * req[1]
            else:
                self.x = req[1]
                self.y = min(req[2], size)     # stored as max(0, H - y) in window coordinates
                self.theta = req[3]
            if self.pen_on:
                canvas.draw_line(old, (self.x, self.y), self.pen)
        self._teleports = []

        if self.last_command is None or now - self.last_command > CMD_TIMEOUT:
            self.vx = self.vy = self.wz = 0.0

        old = (self.x, self.y)
        self.theta = wrap_angle(self.theta + self.wz * dt)
        c, s = math.cos(self.theta), math.sin(self.theta)
        self.x += (c * self.vx - s * self.vy) * dt
        self.y += (s * self.vx + c * self.vy) * dt

        hit = None
        if not (0.0 <= self.x <= size and 0.0 <= self.y <= size):
            hit = (self.x, size - self.y)
            self.x = min(max(self.x, 0.0), size)
            self.y = min(max(self.y, 0.0), size)
        if self.pen_on and (self.x, self.y) != old:
            canvas.draw_line(old, (self.x, self.y), self.pen)
        return hit


class World:
    """All turtles, the drawing layer and the spawn counter."""

    def __init__(self, canvas, background=DEFAULT_BACKGROUND, sprites=1, rng=None):
        self.canvas = canvas
        self.turtles = {}                 # name -> Turtle, in spawn order
        self.counter = 0
        self.background = tuple(background)
        self.sprites = max(1, sprites)
        self._rng = rng
        self.canvas.fill(self.background)

    def _next_sprite(self):
        if self._rng is None:
            return (len(self.turtles) + self.counter) % self.sprites
        return self._rng.randrange(self.sprites)

    def spawn(self, name, x, y, theta):
        """Add a turtle; empty name => 'turtleN'. Returns the name; TurtleError on a duplicate."""
        if not name:
            while True:
                self.counter += 1
                name = 'turtle%d' % self.counter
                if name not in self.turtles:
                    break
        elif name in self.turtles:
            raise TurtleError('A turtled named [%s] already exists' % name)
        self.turtles[name] = Turtle(name, x, y, theta, self._next_sprite())
        return name

    def kill(self, name):
        if name not in self.turtles:
            raise TurtleError('Tried to kill turtle [%s], which does not exist' % name)
        return self.turtles.pop(name)

    def clear(self, background=None):
        """Refill the drawing layer (with a new background colour when given)."""
        if background is not None:
            self.background = tuple(background)
        self.canvas.fill(self.background)

    def reset(self, background=None):
        """Remove every turtle, restart the counter, spawn turtle1 at the centre, clear."""
        removed = list(self.turtles)
        self.turtles.clear()
        self.counter = 0
        self.spawn('', CENTRE, CENTRE, 0.0)
        self.clear(background)
        return removed

    def step(self, dt, now):
        """One tick for every turtle. Returns [(name, hit_position)] of the turtles that hit a wall."""
        hits = []
        for t in list(self.turtles.values()):
            hit = t.step(dt, now, self.canvas)
            if hit is not None:
                hits.append((t.name, hit))
        return hits

    def color_under(self, turtle):
        """RGB of the drawing layer under the turtle's centre."""
        return self.canvas.pixel((turtle.x, turtle.y))
