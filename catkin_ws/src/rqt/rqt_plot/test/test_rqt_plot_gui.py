"""rqt_plot for real: under Xvfb against a private roscore, plotting a sine/cosine publisher."""
import os
import shutil
import subprocess
import sys
import time

import numpy as np
from course_testing import Proc, screenshot, wait_for
from course_testing.image import load_rgb

HERE = os.path.dirname(os.path.abspath(__file__))
BLUE = (0x1f, 0x77, 0xb4)     # first curve
RED = (0xd6, 0x27, 0x28)      # second curve


def _env(roscore, xvfb):
    env = dict(roscore.env, DISPLAY=xvfb.display)
    env.pop('QT_QPA_PLATFORM', None)
    return env


def curve_extent(rgb, color):
    """(number of distinct columns, number of distinct rows) holding exactly `color`."""
    mask = np.all(rgb == np.array(color, np.uint8), axis=2)
    rows, cols = np.nonzero(mask)
    return len(set(cols.tolist())), len(set(rows.tolist())), mask


def test_plots_sine_and_cosine(roscore, xvfb, tmp_path):
    env = _env(roscore, xvfb)
    plot = Proc(['rqt_plot', '/pt/x', '/pt/y'], env=env, log=str(tmp_path / 'rqt_plot.log'))
    pub = None
    try:
        # the topic does not exist yet: it waits and says so
        wait_for(lambda: 'waiting for topic(s) of /pt/x, /pt/y to be published' in plot.output(),
                 30, what='the waiting status line')
        assert plot.alive()
        pub = Proc([sys.executable, os.path.join(HERE, 'sine_publisher.py')], env=env,
                   log=str(tmp_path / 'pub.log'))
        wait_for(lambda: 'plotting /pt/y (geometry_msgs/Point on /pt)' in plot.output(), 30,
                 what='rqt_plot to start plotting')
        assert 'plotting /pt/x (geometry_msgs/Point on /pt)' in plot.output()
        time.sleep(6.0)                          # 1.5 periods of the 4 s wave
        png = str(tmp_path / 'rqt_plot.png')

        def drawn():        # screenshots until both waves span the window (a busy machine draws
            rgb = load_rgb(screenshot(xvfb.display, png))      # later; 60 s hang guard)
            return all(n[0] > 300 and n[1] > 150 for n in (curve_extent(rgb, c) for c in (BLUE, RED)))
        deadline = time.monotonic() + 60
        while not drawn() and time.monotonic() < deadline:
            time.sleep(0.5)
        keep = os.environ.get('COURSE_SCREENSHOT_DIR')
        if keep:
            os.makedirs(keep, exist_ok=True)
            shutil.copy(png, os.path.join(keep, 'rqt_plot_sine.png'))
        assert plot.alive(), plot.output()
    finally:
        if pub:
            pub.stop()
        code = plot.stop()
    rgb = load_rgb(png)
    for name, color in (('x (blue)', BLUE), ('y (red)', RED)):
        ncols, nrows, mask = curve_extent(rgb, color)
        # a wave over ~6 s of a 10 s window: hundreds of columns, and a large span of rows
        assert ncols > 300, '%s curve covers only %d columns' % (name, ncols)
        assert nrows > 150, '%s curve covers only %d rows (flat?)' % (name, nrows)
    # sin and cos are two different curves: in most columns both cover, their rows differ
    _, _, mb = curve_extent(rgb, BLUE)
    _, _, mr = curve_extent(rgb, RED)
    both = np.nonzero(mb.any(axis=0) & mr.any(axis=0))[0]
    rows = np.arange(rgb.shape[0])[:, None]
    mean_b = (rows * mb[:, both]).sum(axis=0) / mb[:, both].sum(axis=0)
    mean_r = (rows * mr[:, both]).sum(axis=0) / mr[:, both].sum(axis=0)
    apart = np.abs(mean_b - mean_r) > 5
    assert len(both) > 300 and apart.mean() > 0.7, \
        'the curves coincide in %.0f%% of %d shared columns' % (100 * (1 - apart.mean()), len(both))
    assert 'Traceback' not in plot.output(), plot.output()
    assert code == 0, plot.output()


def test_bad_fields(roscore, xvfb, tmp_path):
    env = _env(roscore, xvfb)
    pub = Proc([sys.executable, os.path.join(HERE, 'sine_publisher.py')], env=env)
    try:
        wait_for(lambda: '/pt' in subprocess.run(['rostopic', 'list'], env=env, capture_output=True,
                                                 text=True).stdout.split(), 30, what='/pt')
        # no plottable field at all: one error line per field, exit 1
        out = subprocess.run(['rqt_plot', '/pt/w', '/rosout/msg'], env=env, capture_output=True,
                             text=True, timeout=60)
        assert out.returncode == 1
        assert out.stderr.splitlines() == [
            "rqt_plot: ERROR: /pt/w: geometry_msgs/Point has no field 'w' (its fields: x, y, z)",
            'rqt_plot: ERROR: /rosout/msg: field is a string, not a number',
            'rqt_plot: none of the requested fields can be plotted']
        assert 'Traceback' not in out.stdout + out.stderr

        # one bad field among good ones: error line, the rest is plotted
        plot = Proc(['rqt_plot', '/pt/x', '/pt/nope'], env=env, log=str(tmp_path / 'mixed.log'))
        try:
            wait_for(lambda: 'plotting /pt/x' in plot.output(), 30, what='plotting /pt/x')
            assert "ERROR: /pt/nope: geometry_msgs/Point has no field 'nope'" in plot.output()
            time.sleep(1.0)
            assert plot.alive()
        finally:
            assert plot.stop() == 0
    finally:
        pub.stop()

    out = subprocess.run(['rqt_plot', '/pt/x['], env=env, capture_output=True, text=True, timeout=60)
    assert out.returncode == 1
    assert "bad field name 'x['" in out.stderr and 'Traceback' not in out.stderr


def test_no_master(xvfb):
    env = dict(xvfb.env, ROS_MASTER_URI='http://127.0.0.1:9')
    out = subprocess.run(['rqt_plot', '/pt/x'], env=env, capture_output=True, text=True, timeout=60)
    assert out.returncode == 1
    assert out.stderr.strip() == \
        'rqt_plot: cannot reach the ROS master at http://127.0.0.1:9 (is roscore running?)'
