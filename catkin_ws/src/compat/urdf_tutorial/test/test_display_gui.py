"""display.launch with RViz for real: under Xvfb the orange cart is drawn in the 3D view."""
import os
import shutil
import subprocess
import time

import numpy as np
import pytest

from course_testing import Proc, Xvfb, screenshot, wait_for
from course_testing.image import load_rgb

HERE = os.path.dirname(os.path.abspath(__file__))
PKG = os.path.dirname(HERE)
REPO = os.path.abspath(os.path.join(PKG, '..', '..', '..', '..'))
ARTIFACTS = os.path.join(REPO, 'build', 'test-artifacts')


def orange_mask(rgb):
    """Pixels of the cart's orange body (rgba 1 0.45 0) under RViz's lighting: red dominant,
    green about half of red, hardly any blue. Nothing else in the scene has that hue."""
    r, g, b = (rgb[:, :, i].astype(int) for i in range(3))
    return (r > 90) & (g > 0.25 * r) & (g < 0.7 * r) & (b < 0.25 * r)


def green_mask(rgb):
    """Pixels of the green mast (rgba 0.1 0.7 0.2), right of the Displays panel."""
    r, g, b = (rgb[:, :, i].astype(int) for i in range(3))
    green = (g > 80) & (g > 2 * r) & (g > 2 * b)
    green[:, :300] = False
    return green


def _rviz_window(display):
    out = subprocess.run(['xwininfo', '-display', display, '-root', '-tree'],
                         capture_output=True, text=True, timeout=10).stdout
    return 'RViz' in out or 'rviz' in out


def test_display_launch_draws_model(roscore, tmp_path):
    if not shutil.which('xwininfo'):
        pytest.fail('xwininfo (x11-utils, deps/debian.txt) is not installed')
    model = os.path.join(PKG, 'urdf', '02-cart.urdf.xacro')
    with Xvfb(1600, 1000) as x:
        env = dict(roscore.env, DISPLAY=x.display)
        env.pop('QT_QPA_PLATFORM', None)
        launch = Proc(['roslaunch', 'urdf_tutorial', 'display.launch', 'gui:=false',
                       'model:=' + model], env=env, log=str(tmp_path / 'roslaunch.log'))
        try:
            wait_for(lambda: _rviz_window(x.display), 60, 0.5, 'the RViz window')
            # the first frames come before the model is loaded, and the mast (a moving joint)
            # only once its TF arrived: wait for the body and the mast to appear
            shot = str(tmp_path / 'display.png')
            deadline = time.monotonic() + 60
            count = 0
            while time.monotonic() < deadline:
                assert launch.alive(), 'roslaunch exited:\n' + launch.output()[-3000:]
                screenshot(x.display, shot)
                rgb = load_rgb(shot)
                count = int(orange_mask(rgb).sum())
                if count > 2000 and green_mask(rgb).sum() > 300:
                    break
                time.sleep(1.0)
            os.makedirs(ARTIFACTS, exist_ok=True)
            shutil.copy(shot, os.path.join(ARTIFACTS, 'urdf_tutorial_display.png'))
        finally:
            launch.stop()
    rgb = load_rgb(shot)
    mask = orange_mask(rgb)
    assert count > 2000, 'only %d orange pixels: the model is not drawn (see %s)' % (count, shot)
    # the body is in the 3D view (right of the Displays panel), not in a panel or icon
    ys, xs = np.nonzero(mask)
    assert xs.min() > 300, 'orange pixels left of the 3D view at x=%d' % xs.min()
    # the green mast stands on the body: its pixels lie within the body's span
    gys, gxs = np.nonzero(green_mask(rgb))
    assert len(gxs) > 300, 'only %d green mast pixels' % len(gxs)
    assert xs.min() <= gxs.mean() <= xs.max()
