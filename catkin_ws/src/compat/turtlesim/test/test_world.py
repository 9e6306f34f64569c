"""Unit tests of the ROS-free turtle model, the QImage drawing layer and the helper logic."""
import math

import pytest

from turtlesim import square, teleop
from turtlesim.canvas import Canvas
from turtlesim.world import (CENTRE, DEFAULT_BACKGROUND, DEFAULT_PEN, TICK, WORLD_SIZE,
                             TurtleError, World, wrap_angle)


class Recorder:
    """A canvas that remembers what was drawn (for exact checks of the trail segments)."""

    def __init__(self):
        self.lines = []
        self.filled = []

    def fill(self, rgb):
        self.filled.append(rgb)
        self.lines = []

    def draw_line(self, p0, p1, pen):
        self.lines.append((p0, p1, pen.rgb, pen.width))

    def pixel(self, p):
        return self.filled[-1]


def make_world(canvas=None):
    w = World(canvas or Recorder())
    w.spawn('', CENTRE, CENTRE, 0.0)
    return w


def run(world, ticks, now=0.0):
    hits = []
    for k in range(ticks):
        hits += world.step(TICK, now + k * TICK)
    return hits


def test_geometry_constants():
    assert WORLD_SIZE == pytest.approx(11.088889, abs=1e-6)
    assert CENTRE == pytest.approx(5.544445, abs=1e-6)


def test_forward_motion_numbers():
    w = make_world()
    t = w.turtles['turtle1']
    t.command(1.0, 0.0, 0.0, now=0.0)
    run(w, 50)
    assert t.x == pytest.approx(CENTRE + 50 * 0.016, abs=1e-9)   # 0.8 m
    assert t.y == pytest.approx(CENTRE, abs=1e-12)
    assert t.linear_velocity == 1.0


def test_arc_uses_updated_heading_each_tick():
    w = make_world()
    t = w.turtles['turtle1']
    t.command(2.0, 0.0, 1.0, now=0.0)
    run(w, 10)
    x, y, th = CENTRE, CENTRE, 0.0
    for _ in range(10):
        th += 1.0 * TICK
        x += math.cos(th) * 2.0 * TICK
        y += math.sin(th) * 2.0 * TICK
    assert (t.x, t.y, t.theta) == pytest.approx((x, y, th), abs=1e-12)


def test_holonomic_linear_y_is_body_frame():
    w = make_world()
    t = w.turtles['turtle1']
    t.theta = math.pi / 2              # facing +y: body +y is world -x
    t.command(0.0, 1.0, 0.0, now=0.0)
    run(w, 25)
    assert t.x == pytest.approx(CENTRE - 25 * TICK, abs=1e-9)
    assert t.y == pytest.approx(CENTRE, abs=1e-9)
    t.command(3.0, 4.0, 0.0, now=0.0)
    assert t.linear_velocity == 5.0


def test_reverse_reports_positive_speed():
    t = make_world().turtles['turtle1']
    t.command(-2.0, 0.0, 0.0, now=0.0)
    assert t.linear_velocity == 2.0


def test_theta_wraps_to_minus_pi_pi():
    assert wrap_angle(math.pi) == pytest.approx(-math.pi)
    assert wrap_angle(-math.pi) == pytest.approx(-math.pi)
    assert wrap_angle(3 * math.pi / 2) == pytest.approx(-math.pi / 2)
    assert wrap_angle(-7.0) == pytest.approx(-7.0 + 2 * math.pi)
    w = make_world()
    t = w.turtles['turtle1']
    t.command(0.0, 0.0, 10.0, now=0.0)
    for _ in range(200):
        w.step(TICK, 0.5)
        assert -math.pi <= t.theta < math.pi
    assert t.theta == pytest.approx(wrap_angle(200 * 10.0 * TICK), abs=1e-9)


def test_command_timeout_after_one_second_of_wall_time():
    w = make_world()
    t = w.turtles['turtle1']
    t.command(1.0, 0.0, 1.0, now=100.0)
    w.step(TICK, 100.99)
    assert t.linear_velocity == 1.0
    x = t.x
    w.step(TICK, 101.01)
    assert (t.vx, t.vy, t.wz) == (0.0, 0.0, 0.0)
    assert t.x == x


def test_wall_clamp_keeps_command_and_reports_window_coordinates():
    w = make_world()
    t = w.turtles['turtle1']
    t.x = WORLD_SIZE - 0.01
    t.command(1.0, 0.0, 0.0, now=0.0)
    hits = run(w, 3)
    assert t.x == WORLD_SIZE
    assert len(hits) == 3                 # 0.01 m < one step: every tick hits
    name, (hx, hy) = hits[0]
    assert name == 'turtle1'
    assert hx == pytest.approx(WORLD_SIZE - 0.01 + TICK)
    assert hy == pytest.approx(WORLD_SIZE - CENTRE)
    assert t.vx == 1.0
    t.x, t.y = 1.0, 0.005
    t.command(0.0, -1.0, 0.0, now=0.0)
    run(w, 1)
    assert t.y == 0.0 and t.x == pytest.approx(1.0)


def test_teleports_queued_in_order_and_drawn_with_pen():
    rec = Recorder()
    w = make_world(rec)
    t = w.turtles['turtle1']
    t.teleport_absolute(1.0, 2.0, 0.5)
    t.teleport_relative(1.0, math.pi / 2 - 0.5)
    assert (t.x, t.y) == (CENTRE, CENTRE)       # nothing happens before the tick
    w.step(TICK, 0.0)
    assert (t.x, t.y, t.theta) == pytest.approx((1.0, 3.0, math.pi / 2), abs=1e-12)
    assert [(l[0], l[1]) for l in rec.lines] == pytest.approx(
        [((CENTRE, CENTRE), (1.0, 2.0)), ((1.0, 2.0), (1.0, 3.0))])
    assert rec.lines[0][2:] == (DEFAULT_PEN, 3)


def test_teleport_absolute_edges():
    w = make_world()
    t = w.turtles['turtle1']
    t.teleport_absolute(3.0, 50.0, 0.0)          # above the top: lands on y = H, no warning
    assert run(w, 1) == []
    assert t.y == WORLD_SIZE
    t.teleport_absolute(-2.0, 1.0, 4.0)          # left of the world: clamped with a warning
    hits = run(w, 1)
    assert len(hits) == 1 and t.x == 0.0
    assert t.theta == pytest.approx(4.0 - 2 * math.pi)


def test_pen_off_on_and_width_zero():
    rec = Recorder()
    w = make_world(rec)
    t = w.turtles['turtle1']
    t.set_pen(255, 0, 0, 7, 1)          # off: nothing drawn, old pen kept
    t.command(1.0, 0.0, 0.0, now=0.0)
    t.teleport_relative(1.0, 0.0)
    run(w, 5)
    assert rec.lines == []
    assert t.pen.rgb == DEFAULT_PEN
    t.set_pen(10, 20, 30, 0, 0)         # on, width 0 = Qt default 1 px
    run(w, 1)
    assert rec.lines[-1][2:] == ((10, 20, 30), 1)


def test_spawn_naming_and_counter_reset():
    w = make_world()
    assert w.spawn('', 1, 1, 0) == 'turtle2'
    assert w.spawn('turtle3', 1, 1, 0) == 'turtle3'
    assert w.spawn('', 1, 1, 0) == 'turtle4'      # turtle3 exists: skipped
    with pytest.raises(TurtleError, match=r'A turtled named \[turtle2\] already exists'):
        w.spawn('turtle2', 0, 0, 0)
    w.kill('turtle2')
    with pytest.raises(TurtleError, match=r'Tried to kill turtle \[turtle2\], which does not exist'):
        w.kill('turtle2')
    assert w.spawn('', 1, 1, 0) == 'turtle5'      # the counter does not go back
    w.reset()
    assert list(w.turtles) == ['turtle1']
    t = w.turtles['turtle1']
    assert (t.x, t.y, t.theta) == (CENTRE, CENTRE, 0.0)
    assert w.spawn('', 1, 1, 0) == 'turtle2'


def test_qimage_canvas_trail_and_colour_sensor():
    canvas = Canvas()
    w = World(canvas, DEFAULT_BACKGROUND)
    w.spawn('', CENTRE, CENTRE, 0.0)
    t = w.turtles['turtle1']
    assert w.color_under(t) == DEFAULT_BACKGROUND
    t.command(1.0, 0.0, 0.0, now=0.0)
    run(w, 20)
    assert w.color_under(t) == DEFAULT_PEN
    assert canvas.pixel((CENTRE + 0.1, CENTRE)) == DEFAULT_PEN
    assert canvas.pixel((CENTRE + 0.1, CENTRE + 0.1)) == DEFAULT_BACKGROUND  # 4.5 px away
    w.clear((1, 2, 3))
    assert w.color_under(t) == (1, 2, 3)
    assert canvas.pixel((0.0, 0.0)) == (1, 2, 3)
    assert canvas.pixel((WORLD_SIZE, WORLD_SIZE)) == (1, 2, 3)


def test_sprites_are_drawn():
    from turtlesim import sprites
    for i in range(sprites.count()):
        img = sprites.make_sprite(i)
        assert (img.width(), img.height()) == (45, 45)
        opaque = sum(1 for x in range(45) for y in range(45) if (img.pixel(x, y) >> 24) == 255)
        assert 500 < opaque < 45 * 45, 'sprite %d: %d opaque pixels' % (i, opaque)


def test_teleop_key_bindings():
    assert teleop.command_for(0x41, 2.0, 3.0) == (2.0, 0.0)     # up
    assert teleop.command_for(0x42, 2.0, 3.0) == (-2.0, 0.0)    # down
    assert teleop.command_for(0x44, 2.0, 3.0) == (0.0, 3.0)     # left
    assert teleop.command_for(0x43, 2.0, 3.0) == (0.0, -3.0)    # right
    assert teleop.command_for(0x1b, 2.0, 3.0) is None           # ESC
    assert teleop.command_for(ord('['), 2.0, 3.0) is None


class FakePose:
    def __init__(self, x, y, theta, v=0.0, w=0.0):
        self.x, self.y, self.theta, self.linear_velocity, self.angular_velocity = x, y, theta, v, w


def test_square_state_machine_runs_a_square_on_the_model():
    w = make_world()
    t = w.turtles['turtle1']
    driver = square.SquareDriver()
    events = []
    now = 0.0
    for _ in range(4000):
        pose = FakePose(t.x, t.y, t.theta, t.linear_velocity, t.wz)
        lin, ang, event = driver.step(pose)
        if event:
            events.append((event, driver.goal))
        t.command(lin, 0.0, ang, now)
        w.step(TICK, now)
        now += TICK
    goals = [g for e, g in events if e == 'new goal']
    assert len(goals) >= 8
    first, turn = goals[0], goals[1]
    assert (first.x, first.y) == pytest.approx((CENTRE + 2.0, CENTRE))
    assert turn.theta == pytest.approx(math.pi / 2, abs=0.02)
    corner = goals[2]
    assert (corner.x, corner.y) == pytest.approx((CENTRE + 2.0, CENTRE + 2.0), abs=0.2)
