"""Screenshot checks for robot models shown in RViz under Xvfb (used by the description
packages' GUI tests): find RViz's 3D view by its background colour and count the pixels of a
material's colour inside it, whatever the shading (hue/saturation for colours, value for black).
"""
import colorsys
import os
import shutil
import time

import numpy as np

from course_testing.image import load_rgb

BACKGROUND = (48, 48, 48)     # rviz default, also in every rviz config of the course
REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), *(['..'] * 6)))
ARTIFACTS = os.path.join(REPO, 'build', 'test-artifacts')


def view_region(rgb, background=BACKGROUND):
    """(x0, y0, x1, y1) of the 3D view: rows and columns holding many background pixels."""
    bg = np.all(rgb == np.array(background, np.uint8), axis=2)
    cols = np.nonzero(bg.sum(axis=0) > 0.2 * rgb.shape[0])[0]
    rows = np.nonzero(bg.sum(axis=1) > 0.2 * rgb.shape[1])[0]
    if len(cols) == 0 or len(rows) == 0:
        return None
    return int(cols.min()), int(rows.min()), int(cols.max()), int(rows.max())


def _hsv(rgb):
    f = rgb.astype(np.float64) / 255.0
    mx, mn = f.max(axis=2), f.min(axis=2)
    d = mx - mn
    r, g, b = f[..., 0], f[..., 1], f[..., 2]
    h = np.zeros_like(mx)
    nz = d > 1e-9
    rm = nz & (mx == r)
    gm = nz & (mx == g) & ~rm
    bm = nz & ~rm & ~gm
    h[rm] = (60 * (g - b)[rm] / d[rm]) % 360
    h[gm] = 60 * (b - r)[gm] / d[gm] + 120
    h[bm] = 60 * (r - g)[bm] / d[bm] + 240
    s = np.where(mx > 0, d / np.maximum(mx, 1e-9), 0)
    return h, s, mx


def colour_mask(rgb, rgba, hue_tol=12.0):
    """Pixels that show a surface of colour `rgba` (floats 0..1) under RViz's lighting."""
    h, s, v = _hsv(rgb)
    hue, sat, val = colorsys.rgb_to_hsv(*rgba[:3])
    if val < 0.05:                                    # black: darker than the background
        return v < 0.12
    if sat < 0.25:
        raise ValueError('colour %s is too grey to be told from the scene' % (rgba,))
    dh = np.abs((h - hue * 360 + 180) % 360 - 180)
    return (dh < hue_tol) & (s > 0.5 * sat) & (v > 0.12)


def count_in_view(rgb, rgba, box):
    x0, y0, x1, y1 = box
    return int(colour_mask(rgb[y0:y1 + 1, x0:x1 + 1], rgba).sum())


def keep(path, name):
    os.makedirs(ARTIFACTS, exist_ok=True)
    shutil.copy(path, os.path.join(ARTIFACTS, name))


def wait_for_colours(display, shot_path, colours, min_fraction=0.003, timeout=90.0, settle=8.0):
    """Screenshot `display` every 2 s (after `settle`) until every {name: rgba} covers at least
    min_fraction of the 3D view; returns (box, {name: pixels}) of the last shot. Raises
    AssertionError naming what is missing after `timeout`."""
    from course_testing import screenshot
    time.sleep(settle)
    deadline = time.monotonic() + timeout
    while True:
        screenshot(display, shot_path)
        rgb = load_rgb(shot_path)
        box = view_region(rgb)
        counts = {}
        if box:
            area = (box[2] - box[0] + 1) * (box[3] - box[1] + 1)
            counts = {n: count_in_view(rgb, c, box) for n, c in colours.items()}
            missing = [n for n, k in counts.items() if k < min_fraction * area]
            if not missing:
                return box, counts
        if time.monotonic() > deadline:
            raise AssertionError('RViz view %s: colours missing or too few pixels %s (need %.1f%% each); see %s'
                                 % (box, counts, 100 * min_fraction, shot_path))
        time.sleep(2.0)


def rviz_launch_shows(env, display, tmp_path, launch, colours, artifact, launch_args=()):
    """roslaunch `launch` (a [pkg, file] list) with `env`, wait until RViz shows every colour,
    keep the screenshot as build/test-artifacts/`artifact`; returns (box, counts)."""
    from course_testing import Proc
    log = os.path.join(str(tmp_path), 'launch.log')
    p = Proc(['roslaunch'] + list(launch) + list(launch_args), env=env, log=log)
    shot = os.path.join(str(tmp_path), artifact)
    try:
        try:
            return wait_for_colours(display, shot, colours)
        except AssertionError as e:
            raise AssertionError('%s\nlaunch log tail:\n%s' % (e, p.output()[-3000:]))
        finally:
            if os.path.exists(shot):
                keep(shot, artifact)
    finally:
        p.stop()
