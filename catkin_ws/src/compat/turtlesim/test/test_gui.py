"""turtlesim_node with a real window under Xvfb: screenshots show background, trail and sprite."""
import os
import shutil
import subprocess
import time

import numpy as np
import pytest

from course_testing import Proc, screenshot, wait_for
from course_testing.image import load_rgb

SIZE = 499.0 / 45.0
BACKGROUND = (69, 86, 255)
PEN = (179, 184, 255)
ARTIFACTS = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.dirname(os.path.dirname(os.path.abspath(__file__))))))), 'build', 'test-artifacts')


def region(rgb, colour):
    """Bounding box (x0, y0, x1, y1) of the pixels of exactly `colour`, or None."""
    ys, xs = np.nonzero(np.all(rgb == np.array(colour, np.uint8), axis=2))
    if len(xs) == 0:
        return None
    return xs.min(), ys.min(), xs.max(), ys.max()


def px(box, x, y):
    """Screen pixel of world point (x, y) inside the window whose canvas is `box`."""
    return int(round(box[0] + x * 45.0)), int(round(box[1] + (SIZE - y) * 45.0))


def ros(env, *cmd):
    subprocess.run(list(cmd), env=env, check=True, timeout=20, capture_output=True)


def pose(env):
    out = subprocess.run(['rostopic', 'echo', '-n', '1', '/turtle1/pose'], env=env,
                         capture_output=True, text=True, timeout=15).stdout
    return {k: float(v) for k, v in (l.split(': ') for l in out.splitlines() if ': ' in l)}


def keep(path, name):
    os.makedirs(ARTIFACTS, exist_ok=True)
    shutil.copy(path, os.path.join(ARTIFACTS, name))


def settled_shot(display, path, check, timeout=30.0):
    """Screenshots until CHECK(rgb) finds no problem (the window repaints on its own timer, later
    on a busy machine) or the timeout passed (a hang guard): the last picture and its problem."""
    deadline = time.monotonic() + timeout
    while True:
        rgb = load_rgb(screenshot(display, path))
        problem = check(rgb)
        if problem is None or time.monotonic() > deadline:
            return rgb, problem
        time.sleep(0.2)


def trail_problem(rgb, end):
    """What is wrong with the picture of the canvas, the trail and the sprite at END, or None."""
    box = region(rgb, BACKGROUND)
    if box is None:
        return 'no background-coloured window on the screen'
    w, h = box[2] - box[0] + 1, box[3] - box[1] + 1
    if (w, h) != (500, 500):
        return 'background region %dx%d, expected the 500x500 canvas' % (w, h)
    # trail pixels where the turtle went: along the teleport diagonal and the drive line
    for x, y in ((3.0, 3.0), (4.5, 4.5), (2.5, 2.0), (3.0, 2.0)):
        sx, sy = px(box, x, y)
        if tuple(rgb[sy, sx]) != PEN:
            return 'no trail at world (%s, %s)' % (x, y)
    # and not elsewhere
    sx, sy = px(box, 8.0, 8.0)
    if tuple(rgb[sy, sx]) != BACKGROUND:
        return 'a trail at world (8, 8)'
    # the sprite: many pixels that are neither background nor pen around the pose
    cx, cy = px(box, end['x'], end['y'])
    patch = rgb[cy - 22:cy + 23, cx - 22:cx + 23].reshape(-1, 3)
    other = [p for p in map(tuple, patch) if p not in (BACKGROUND, PEN)]
    if len(other) <= 300:
        return 'no turtle sprite at the pose (%d pixels)' % len(other)
    far = rgb[px(box, 8, 8)[1] - 22:px(box, 8, 8)[1] + 23,
              px(box, 8, 8)[0] - 22:px(box, 8, 8)[0] + 23].reshape(-1, 3)
    if not all(tuple(p) == BACKGROUND for p in far):
        return 'a sprite away from the pose'
    # the sprite is rotated with theta: it is longer along x (heading 0) than along y
    mask = ~np.all((rgb[cy - 22:cy + 23, cx - 22:cx + 23] == BACKGROUND)
                   | (rgb[cy - 22:cy + 23, cx - 22:cx + 23] == PEN), axis=2)
    ys, xs = np.nonzero(mask)
    if not xs.max() - xs.min() > ys.max() - ys.min():
        return 'the sprite is not longer along x (heading 0)'
    return None


def cleared_problem(rgb):
    """What is wrong with the canvas after /clear with the new background, or None."""
    if region(rgb, BACKGROUND) is not None:
        return 'the old background is still on the screen'
    box2 = region(rgb, (200, 30, 30))
    if box2 is None or box2[2] - box2[0] + 1 != 500 or box2[3] - box2[1] + 1 != 500:
        return 'no 500x500 canvas of the new background: %s' % (box2,)
    sx, sy = px(box2, 3.0, 3.0)
    if tuple(rgb[sy, sx]) != (200, 30, 30):
        return 'the trail survived /clear'
    return None


def test_window_background_trail_sprite_and_clear(roscore, xvfb, tmp_path):
    env = dict(roscore.env, DISPLAY=xvfb.display)
    env.pop('QT_QPA_PLATFORM', None)
    sim = Proc(['rosrun', 'turtlesim', 'turtlesim_node'], env=env, log=str(tmp_path / 'sim.log'))
    try:
        wait_for(lambda: pose(env), 30, 0.2, 'the first pose')
        # a diagonal trail (teleport with the pen on), then 2 m/s along +x for 1 s
        ros(env, 'rosservice', 'call', '/turtle1/teleport_absolute', '2.0', '2.0', '0.0')
        ros(env, 'rostopic', 'pub', '-1', '/turtle1/cmd_vel', 'geometry_msgs/Twist',
            '{linear: {x: 2.0}}')
        end = wait_for(lambda: (lambda p: p if p['linear_velocity'] == 0.0 and p['x'] > 3.5
                                else None)(pose(env)), 10, 0.1, 'the turtle to drive and stop')
        shot = str(tmp_path / 'trail.png')
        rgb, problem = settled_shot(xvfb.display, shot, lambda rgb: trail_problem(rgb, end))
        keep(shot, 'turtlesim_trail.png')
        assert problem is None, problem

        # new background: only visible after /clear, which also wipes the trail
        for c, v in zip('rgb', (200, 30, 30)):
            ros(env, 'rosparam', 'set', '/turtlesim/background_' + c, str(v))
        time.sleep(0.3)
        rgb = load_rgb(screenshot(xvfb.display, str(tmp_path / 'before_clear.png')))
        assert region(rgb, BACKGROUND) is not None
        ros(env, 'rosservice', 'call', '/clear')
        shot = str(tmp_path / 'cleared.png')
        rgb, problem = settled_shot(xvfb.display, shot, cleared_problem)
        keep(shot, 'turtlesim_cleared.png')
        assert problem is None, problem
        assert sim.alive()
    finally:
        assert sim.stop() is not None
    assert 'Traceback' not in sim.output()


def test_window_title(roscore, xvfb, tmp_path):
    if not shutil.which('xwininfo'):
        pytest.fail('xwininfo (x11-utils, deps/debian.txt) is not installed')
    env = dict(roscore.env, DISPLAY=xvfb.display)
    env.pop('QT_QPA_PLATFORM', None)
    sim = Proc(['rosrun', 'turtlesim', 'turtlesim_node'], env=env, log=str(tmp_path / 'sim.log'))
    try:
        def tree():
            return subprocess.run(['xwininfo', '-display', xvfb.display, '-root', '-tree'],
                                  capture_output=True, text=True, timeout=10).stdout
        out = wait_for(lambda: (lambda t: t if '"TurtleSim"' in t else None)(tree()), 30, 0.3,
                       'a window titled TurtleSim')
        line = [l for l in out.splitlines() if '"TurtleSim"' in l][0]
        assert '500x500' in line
    finally:
        sim.stop()
