"""Run by test_editor_scenario.py in a process of its own (pytest-qt on that test's Xvfb and
roscore; not collected by the test run itself): the rest of the window's editing, by clicks and
drags on the real widgets against the real simulator — toolbar sphere and point light, the
property view, Translate and Rotate by dragging over the ground, Edit -> Reset Model Poses and
Reset World, the wall tool, a second window on the same simulator, Save World As."""
import math
import os
import xml.etree.ElementTree as ET

import numpy as np
from PyQt5 import QtCore, QtGui, QtWidgets

from course_testing import screenshot
from course_testing.image import load_rgb
from ode_sim_gui.client import SimClient
from ode_sim_gui.window import MainWindow
from scenario_common import open_window, wait_until

OUT = os.environ.get('SCENARIO_OUT', '/tmp')


def px_of(win, x, y, z=0.0):
    p = win.view.camera.project((x, y, z))
    return QtCore.QPointF(p[0], p[1])


def drag(widget, points, button=QtCore.Qt.LeftButton):
    """A mouse drag through `points` as the X server delivers it (pressed button on moves)."""
    send = QtWidgets.QApplication.sendEvent
    E = QtGui.QMouseEvent
    nomod = QtCore.Qt.NoModifier
    send(widget, E(E.MouseButtonPress, points[0], button, button, nomod))
    for p in points[1:]:
        send(widget, E(E.MouseMove, p, QtCore.Qt.NoButton, button, nomod))
        QtWidgets.QApplication.processEvents()
    send(widget, E(E.MouseButtonRelease, points[-1], button, QtCore.Qt.NoButton, nomod))


def line(win, a, b, n=8):
    return [px_of(win, a[0] + (b[0] - a[0]) * i / n, a[1] + (b[1] - a[1]) * i / n)
            for i in range(n + 1)]


def toolbar_click(qtbot, win, action):
    tb = win.findChild(QtWidgets.QToolBar, 'tools')
    qtbot.mouseClick(tb.widgetForAction(action), QtCore.Qt.LeftButton)


def place_sphere_and_light(qtbot, win):
    # toolbar: a sphere and a point light, each placed by a click on the ground
    toolbar_click(qtbot, win, win.act_shapes['sphere'])
    qtbot.mouseClick(win.view, QtCore.Qt.LeftButton, pos=px_of(win, 1.0, 0.0).toPoint())
    wait_until(qtbot, lambda: 'unit_sphere' in win.scene.model_names(), 60, 'the sphere')
    toolbar_click(qtbot, win, win.act_lights['point'])
    qtbot.mouseClick(win.view, QtCore.Qt.LeftButton, pos=px_of(win, 0.0, 2.0).toPoint())
    wait_until(qtbot, lambda: any(l.name == 'user_point_light' for l in win.scene.lights()), 60,
               'the light')
    light = [l for l in win.scene.lights() if l.name == 'user_point_light'][0]
    assert light.type == 'point' and np.allclose(light.pose.p, (0, 2, 1), atol=0.05)
    tree_names = [it.text(0) for it in win.world_panel.tree.findItems(
        'user_point_light', QtCore.Qt.MatchStartsWith | QtCore.Qt.MatchRecursive)]
    assert tree_names == ['user_point_light (point)']

    # select the sphere: its properties come from the simulator
    wait_until(qtbot, lambda: win.scene.bounds('unit_sphere') is not None, 30, 'sphere pose')
    qtbot.mouseClick(win.view, QtCore.Qt.LeftButton, pos=px_of(win, 1.0, 0.0, 0.5).toPoint())
    wait_until(qtbot, lambda: win.scene.selected == 'unit_sphere', 10, 'sphere selected')
    wp = win.world_panel
    assert (wp.lbl_name.text(), wp.lbl_mass.text(), wp.lbl_static.text(),
            wp.lbl_self_collide.text()) == ('unit_sphere', '1', 'false', 'false')


def translate_rotate_follow_reset(qtbot, win):
    # Translate: drag it over the ground to (2.5, -1)
    toolbar_click(qtbot, win, win.act_modes['translate'])
    drag(win.view, line(win, (1.0, 0.0), (2.5, -1.0)))
    wait_until(qtbot, lambda: np.allclose(win.scene.model_pose('unit_sphere').p[:2], (2.5, -1.0),
                                          atol=0.1), 30, 'the sphere at (2.5, -1)')
    # Rotate: it turns about the vertical towards the cursor
    toolbar_click(qtbot, win, win.act_modes['rotate'])
    drag(win.view, line(win, (3.5, -1.0), (2.5, 0.5)))
    wait_until(qtbot, lambda: abs(win.scene.model_pose('unit_sphere').rpy()[2] - math.pi / 2)
               < 0.1, 30, 'the sphere turned to 90 degrees')
    toolbar_click(qtbot, win, win.act_modes['select'])
    win.select('unit_sphere')

    # Camera -> Follow: the view's focus goes with the selected model
    win.act_follow.trigger()
    assert win.act_follow.isChecked()
    # Edit -> Reset Model Poses: back where it was inserted (and the camera follows it there)
    win.act_reset_poses.trigger()
    wait_until(qtbot, lambda: np.allclose(win.scene.model_pose('unit_sphere').p[:2], (1.0, 0.0),
                                          atol=0.05), 30, 'the sphere back at (1, 0)')
    wait_until(qtbot, lambda: np.allclose(win.view.camera.focus[:2], (1.0, 0.0), atol=0.05), 10,
               'the camera to follow the sphere')
    win.act_follow.trigger()
    assert not win.act_follow.isChecked()
    win.view.camera.look_at((0.0, -7.0, 9.0), (0.0, 0.0, 0.0))


def draw_walls(qtbot, win):
    # the wall tool: two walls dragged on the ground, Enter -> one static model
    before = load_rgb(screenshot(os.environ['DISPLAY'], os.path.join(OUT, 'before_walls.png')))
    toolbar_click(qtbot, win, win.act_wall)
    drag(win.view, line(win, (-3.0, -2.0), (3.0, -2.0)))
    drag(win.view, line(win, (-3.0, -2.0), (-3.0, 3.0)))
    assert len(win.wall_segments) == 2
    win.view.setFocus()
    qtbot.keyClick(win.view, QtCore.Qt.Key_Return)
    wait_until(qtbot, lambda: 'walls' in win.scene.model_names(), 60, 'the walls model')
    walls = win.scene.model('walls')
    assert walls.static and len(walls.links) == 1 and len(walls.links[0].visuals) == 2
    win.select(None)
    win.view.update()
    qtbot.wait(800)
    after = load_rgb(screenshot(os.environ['DISPLAY'], os.path.join(OUT, 'walls.png')))
    tl = win.view.mapToGlobal(QtCore.QPoint(0, 0))
    for x, y in ((0.0, -2.0), (-3.0, 0.5)):
        p = px_of(win, x, y, 1.25)
        cx, cy = int(p.x()) + tl.x(), int(p.y()) + tl.y()
        d = np.abs(after[cy - 4:cy + 5, cx - 4:cx + 5].astype(int)
                   - before[cy - 4:cy + 5, cx - 4:cx + 5].astype(int)).sum(axis=2)
        assert (d > 30).mean() > 0.5, 'the wall at (%g, %g) is not drawn' % (x, y)


def test_editing_in_the_window(qtbot, ros):
    win = open_window(qtbot, 'ground_plane', 'the world')
    win.view.camera.look_at((0.0, -7.0, 9.0), (0.0, 0.0, 0.0))
    win.view.update()
    place_sphere_and_light(qtbot, win)
    translate_rotate_follow_reset(qtbot, win)
    draw_walls(qtbot, win)

    # a second window on the same simulator sees the same world; closing it changes nothing
    other = MainWindow(SimClient('/gazebo'))
    qtbot.addWidget(other)
    other.show()
    wait_until(qtbot, lambda: set(other.scene.model_names()) == set(win.scene.model_names()),
               60, 'the second window to show the world')
    other.close()
    it = win.client.stats.iterations
    wait_until(qtbot, lambda: win.client.stats.iterations > it + 100, 30, 'the simulation runs on')

    # Edit -> Reset World: the time starts again
    t = win.client.stats.sim_time.to_sec()
    assert t > 1.0
    win.act_reset_world.trigger()
    wait_until(qtbot, lambda: win.client.stats.sim_time.to_sec() < t - 0.5, 30,
               'the sim time reset')

    # File -> Save World As keeps the light, the shapes and the walls
    saved = os.path.join(OUT, 'edited.world')
    QtWidgets.QFileDialog.getSaveFileName = staticmethod(lambda *a, **k: (saved, ''))
    win.act_save.trigger()
    w = ET.parse(saved).getroot().find('world')
    assert 'user_point_light' in [l.get('name') for l in w.iter('light')]
    names = [m.get('name') for m in w.findall('model')] + \
        [i.findtext('name') for i in w.findall('include')]
    assert {'unit_sphere', 'walls'} <= set(names), names
    win.close()
