"""rqt_gui for real under Xvfb with a private master: the Plugins menu built from exported
plugin.xml files (a tutorial plugin written here loads unchanged; broken ones are reported and the
window stays up), Message Publisher publishing a Float64 that `rostopic echo` receives, Plot
plotting it (checked in a screenshot), and the Plot + Publisher perspective exported and reloaded."""
import json
import os
import shutil
import sys

import numpy as np
from course_testing import Proc, screenshot, wait_for
from course_testing.image import load_rgb
from course_testing.rqt_driver import gui_env, states

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from plugin_fixtures import write_packages  # noqa: E402

BLUE = (0x1f, 0x77, 0xb4)     # rqt_plot's first curve


def by_kind(output, kind):
    for s in states(output):
        if 'error' in s:
            raise AssertionError('scripted rqt_gui failed: %s\n%s' % (s['error'], output[-3000:]))
        if s.get('kind') == kind:
            return s
    return None


def test_rqt_gui_plugins_publisher_plot_perspective(roscore, screen, tmp_path):
    xvfb = screen            # 1600x1000: room for both docks
    env = gui_env(roscore.env, xvfb.display, tmp_path / 'config')
    env['ROS_PACKAGE_PATH'] = write_packages(tmp_path / 'pkgs') + os.pathsep + env.get('ROS_PACKAGE_PATH', '')
    flag, perspective = tmp_path / 'shot.done', tmp_path / 'plot_pub.perspective'
    procs = []
    try:
        gui = Proc([sys.executable, os.path.join(HERE, 'check_rqt_driver.py'), 'build', str(flag),
                    str(perspective)], env=env, log=str(tmp_path / 'build.log'))
        procs.append(gui)
        echo = Proc(['rostopic', 'echo', '-n', '5', '/rqt_test/value'], env=env, log=str(tmp_path / 'echo.log'))
        procs.append(echo)
        wait_for(lambda: by_kind(gui.output(), 'plotted') or not gui.alive(), 90, 0.3,
                 'the publisher to publish and Plot to plot /rqt_test/value/data')
        out = gui.output()
        menu, broken, publishing, plotted = [by_kind(out, k) for k in ('menu', 'broken', 'publishing', 'plotted')]
        assert plotted, out[-3000:]
        png = screenshot(xvfb.display, str(tmp_path / 'rqt_gui.png'))
        keep = os.environ.get('COURSE_SCREENSHOT_DIR')
        if keep:
            os.makedirs(keep, exist_ok=True)
            shutil.copy(png, os.path.join(keep, 'rqt_gui_plot_publisher.png'))
        wait_for(lambda: 'data:' in echo.output(), 30, 0.2, 'rostopic echo to receive /rqt_test/value')
        flag.write_text('done')
        wait_for(lambda: not gui.alive(), 30, 0.2, 'rqt_gui to close')
        out = gui.output()
        exported = by_kind(out, 'exported')
        assert gui.popen.returncode == 0 and exported, out[-3000:]

        # reload the exported perspective in a new rqt_gui
        gui2 = Proc([sys.executable, os.path.join(HERE, 'check_rqt_driver.py'), 'reload',
                     '--perspective-file', str(perspective)], env=env, log=str(tmp_path / 'reload.log'))
        procs.append(gui2)
        wait_for(lambda: not gui2.alive(), 60, 0.2, 'the reloading rqt_gui to report and close')
        reloaded = by_kind(gui2.output(), 'reloaded')
        assert gui2.popen.returncode == 0 and reloaded, gui2.output()[-3000:]
        echo_text = echo.output()
    finally:
        for p in reversed(procs):
            p.stop()

    check_menu_and_broken_plugins(menu, broken)
    check_publisher(publishing, echo_text)
    check_plot(plotted, png)
    check_perspective(perspective, reloaded, plotted['docks'])


def check_menu_and_broken_plugins(menu, broken):
    # Plugins menu: groups as submenus, the tutorial's label, the test packages found
    assert ['Examples', 'My first Python Plugin', 'rqt_mypkg/My Plugin'] in menu['menu']
    assert ['Topics', 'Message Publisher', 'rqt_publisher/Publisher'] in menu['menu']
    assert ['Introspection', 'Node Graph', 'rqt_graph/RosGraph'] in menu['menu']
    assert any('rqt_badxml' in e and 'could not parse plugin.xml' in e for e in menu['errors']), menu['errors']
    # the tutorial plugin loaded twice (serials 1, 2), the broken ones reported, window alive
    assert broken['window_visible']
    assert 'rqt_mypkg/My Plugin#1' in broken['running'] and 'rqt_mypkg/My Plugin#2' in broken['running']
    assert not any(r.startswith('rqt_broken') for r in broken['running'])
    titles = sorted(d['title'] for d in broken['docks'].values())
    assert titles == ['My Plugin Title', 'My Plugin Title (2)'], broken['docks']
    assert 'rqt_mypkg__My Plugin__1__MyPluginUi' in broken['docks']
    assert broken['tutorial_saved'] == [None]
    assert any('could not load plugin "rqt_broken/Raises": RuntimeError: boom in __init__' in e
               for e in broken['errors']), broken['errors']
    assert any('could not find class "NoSuchClass" in module "rqt_broken.broken"' in e
               for e in broken['errors']), broken['errors']
    assert 'HalfUi' not in json.dumps(broken['docks'])          # the half-built widget is gone


def check_publisher(publishing, echo_text):
    # publisher: an unknown type is one status line; the Float64 rows; rostopic echo got i * 0.5
    assert publishing['bad_type_id'] is None
    assert 'could not find type "no_such_pkg/NoSuchType"' in publishing['status']
    assert publishing['rows'][0][:4] == ['/rqt_test/value', 'std_msgs/Float64', '10.00', True]
    assert publishing['rows'][0][4] == [['data', 'i * 0.5']]
    values = [float(l.split(':')[1]) for l in echo_text.splitlines() if l.startswith('data:')]
    assert len(values) >= 2 and all(v > 0 and (v * 2).is_integer() for v in values), echo_text
    assert values == sorted(values) and values[1] - values[0] == 0.5, values


def check_plot(plotted, png):
    # Plot and Message Publisher docked together (both visible, side by side or stacked)
    assert plotted['points'] >= 20 and plotted['last'] > 0
    d = plotted['docks']
    assert 'rqt_plot__Plot__1__PlotWidgetUi' in d and 'rqt_publisher__Publisher__1__PublisherUi' in d
    assert not any(v['floating'] for v in d.values())
    # the plotted curve is on screen, in Plot's dock
    rgb = load_rgb(png)
    x, y, w, h = plotted['plot_rect']
    mask = np.all(rgb[y:y + h, x:x + w] == np.array(BLUE, np.uint8), axis=2)
    cols = np.nonzero(mask.any(axis=0))[0]
    rows = np.nonzero(mask.any(axis=1))[0]
    assert len(cols) > 50 and len(rows) > 20, \
        'the curve covers %d columns and %d rows of the plot' % (len(cols), len(rows))


def check_perspective(perspective, reloaded, d):
    # the perspective file and its reload
    data = json.load(open(perspective))
    assert 'mainwindow' in data['groups'] and 'pluginmanager' in data['groups']
    assert reloaded['perspective'] == '@plot_pub'
    assert reloaded['running'] == ['rqt_plot/Plot#1', 'rqt_publisher/Publisher#1']
    assert sorted(reloaded['docks']) == sorted(d)
    assert reloaded['rows'] == [['/rqt_test/value', 'std_msgs/Float64', '2.00', False, [['data', 'i * 0.5']]]]
    assert reloaded['plot_specs'] == ['/rqt_test/value/data']
