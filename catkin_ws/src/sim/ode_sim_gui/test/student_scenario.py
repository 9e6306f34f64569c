"""Run by test_student_scenario.py in a process of its own (pytest + pytest-qt on that test's
Xvfb and roscore; not collected by the test run itself): a student builds a scene in the window
as PW4 and lab 4 do — inserts three library models and a box, moves one, deletes one, pauses and
steps 100 steps, saves the world — with mouse clicks and key presses on the real widgets, and
screenshots of the screen show the inserted models. Writes $SCENARIO_OUT/expected.json (the
models and their poses at saving) and screenshots to $SCENARIO_OUT."""
import json
import os

import numpy as np
from PyQt5 import QtCore, QtWidgets

from course_testing import screenshot
from course_testing.image import load_rgb
from scenario_common import open_window, wait_until

OUT = os.environ.get('SCENARIO_OUT', '/tmp')
LIBRARY = ['traffic_cone', 'potted_plant', 'barrel']
PLACES = {'traffic_cone': (1.5, -1.5), 'potted_plant': (-1.5, -1.5), 'barrel': (1.5, 1.5),
          'box': (-1.5, 1.5)}


def click(qtbot, widget, x, y, button=QtCore.Qt.LeftButton):
    qtbot.mouseClick(widget, button, pos=QtCore.QPoint(int(round(x)), int(round(y))))


def ground_click(qtbot, win, x, y):
    px = win.view.camera.project((x, y, 0.0))
    assert px is not None and 0 <= px[0] < win.view.width() and 0 <= px[1] < win.view.height()
    click(qtbot, win.view, *px)


def shot(win, name):
    """A screenshot of the whole screen (ImageMagick's import, as a user would take it) and the
    view's rectangle in it."""
    QtWidgets.QApplication.processEvents()
    path = os.path.join(OUT, name)
    screenshot(os.environ['DISPLAY'], path)
    tl = win.view.mapToGlobal(QtCore.QPoint(0, 0))
    return load_rgb(path).astype(int), (tl.x(), tl.y())


def region(rgb, origin, px, half=6):
    x, y = int(round(px[0])) + origin[0], int(round(px[1])) + origin[1]
    return rgb[y - half:y + half + 1, x - half:x + half + 1]


def insert_models(qtbot, win):
    # Insert tab: click a model, then click on the ground
    win.tabs.setCurrentWidget(win.insert_panel)
    lst = win.insert_panel.list
    wait_until(qtbot, lambda: win.insert_panel.entries, 60, 'the model library')
    for name in LIBRARY:
        items = [lst.item(i) for i in range(lst.count())
                 if lst.item(i).data(QtCore.Qt.UserRole) is not None
                 and lst.item(i).data(QtCore.Qt.UserRole).name == name]
        assert items, 'model %s is not in the Insert tab' % name
        lst.scrollToItem(items[0])
        rect = lst.visualItemRect(items[0])
        click(qtbot, lst.viewport(), rect.center().x(), rect.center().y())
        assert win.view.mode == 'place'
        ground_click(qtbot, win, *PLACES[name])
        wait_until(qtbot, lambda: name in win.scene.model_names(), 60, 'inserted %s' % name)
    # the toolbar's box
    tb = win.findChild(QtWidgets.QToolBar, 'tools')
    qtbot.mouseClick(tb.widgetForAction(win.act_shapes['box']), QtCore.Qt.LeftButton)
    ground_click(qtbot, win, *PLACES['box'])
    wait_until(qtbot, lambda: 'unit_box' in win.scene.model_names(), 60, 'the box')


def move_and_delete(qtbot, win):
    # move one: select the barrel by clicking on it, type a new x in the World tab
    win.tabs.setCurrentWidget(win.world_panel)
    wait_until(qtbot, lambda: win.scene.bounds('barrel') is not None, 30, 'barrel pose')
    lo, hi = win.scene.bounds('barrel')
    click(qtbot, win.view, *win.view.camera.project((lo + hi) / 2))
    wait_until(qtbot, lambda: win.scene.selected == 'barrel', 10, 'barrel selected')
    xbox = win.world_panel.pose_boxes[0]
    xbox.selectAll()
    qtbot.mouseClick(xbox, QtCore.Qt.LeftButton)
    xbox.lineEdit().selectAll()
    qtbot.keyClicks(xbox.lineEdit(), '2.5')
    qtbot.keyClick(xbox.lineEdit(), QtCore.Qt.Key_Return)
    win.view.setFocus()
    wait_until(qtbot, lambda: abs(win.scene.model_pose('barrel').p[0] - 2.5) < 1e-3, 30,
               'the barrel at x 2.5')
    # delete one: click the potted plant, press Delete
    lo, hi = win.scene.bounds('potted_plant')
    click(qtbot, win.view, *win.view.camera.project((lo + hi) / 2))
    wait_until(qtbot, lambda: win.scene.selected == 'potted_plant', 10, 'plant selected')
    qtbot.keyClick(win.view, QtCore.Qt.Key_Delete)
    wait_until(qtbot, lambda: 'potted_plant' not in win.scene.model_names(), 30, 'plant deleted')


def pause_and_step_100(qtbot, win):
    """The step size of the world."""
    # pause, then step 100 steps: sim time advances by exactly 100 x step
    qtbot.mouseClick(win.btn_play, QtCore.Qt.LeftButton)
    wait_until(qtbot, lambda: win.client.stats is not None and win.client.stats.paused, 30,
               'paused')
    # settled: two statistics messages in a row with the same iteration count
    last = [None]

    def settled():
        s = win.client.stats
        same = last[0] is not None and s is not last[0] and s.iterations == last[0].iterations
        if s is not last[0]:
            last[0] = s
        return same
    wait_until(qtbot, settled, 30, 'the paused world to settle')
    s0 = win.client.stats
    it0, step = s0.iterations, s0.max_step_size
    win.spin_steps.setFocus()
    win.spin_steps.lineEdit().selectAll()
    qtbot.keyClicks(win.spin_steps.lineEdit(), '100')
    assert win.spin_steps.value() == 100
    qtbot.mouseClick(win.btn_step, QtCore.Qt.LeftButton)
    wait_until(qtbot, lambda: win.client.stats.iterations == it0 + 100, 30, '100 steps')
    s1 = win.client.stats
    assert s1.paused
    # exactly 100 steps (nanosecond rounding of the time stamps aside)
    assert abs((s1.sim_time - s0.sim_time).to_nsec() - 100 * step * 1e9) <= 1
    wait_until(qtbot, lambda: win.lbl_iter.text() == 'Iterations: %d' % (it0 + 100), 10,
               'the bottom bar to show the iterations')
    qtbot.wait(1000)
    assert win.client.stats.iterations == it0 + 100             # and it stays paused
    return step


def check_screenshot(qtbot, win, before, origin):
    # screenshots: every inserted model is drawn (pixels differ from the empty scene there)
    win.select(None)
    win.view.camera.look_at((0.0, -6.0, 7.0), (0.0, 0.0, 0.0))
    win.view.update()
    qtbot.wait(500)
    after, origin = shot(win, 'scene.png')
    for name in ('traffic_cone', 'barrel', 'unit_box'):
        lo, hi = win.scene.bounds(name)
        px = win.view.camera.project((lo + hi) / 2)
        diff = np.abs(region(after, origin, px) - region(before, origin, px)).sum(axis=2)
        assert (diff > 60).mean() > 0.5, '%s is not drawn at %s' % (name, px)
    # the deleted plant is not
    px = win.view.camera.project((PLACES['potted_plant'][0], PLACES['potted_plant'][1], 0.3))
    diff = np.abs(region(after, origin, px, 3) - region(before, origin, px, 3)).sum(axis=2)
    assert (diff > 60).mean() < 0.2


def save_world(win, step):
    # File -> Save World As
    saved = os.path.join(OUT, 'my_scene.world')
    QtWidgets.QFileDialog.getSaveFileName = staticmethod(lambda *a, **k: (saved, ''))
    win.act_save.trigger()
    assert os.path.isfile(saved)
    _, models = win.client.poses()
    expected = {n: [list(map(float, p.p)), list(map(float, p.q))] for n, p in models.items()}
    assert set(expected) >= {'my_robot_model', 'traffic_cone', 'barrel', 'unit_box'}
    assert 'potted_plant' not in expected
    with open(os.path.join(OUT, 'expected.json'), 'w') as f:
        json.dump({'world': saved, 'models': expected, 'step': step}, f)


def test_student_builds_saves_a_scene(qtbot, ros):
    win = open_window(qtbot, 'my_robot_model', 'the robot in the window')
    # the camera looks at the scene from above, as a student would turn it
    win.view.camera.look_at((0.0, -6.0, 7.0), (0.0, 0.0, 0.0))
    win.view.update()
    before, origin = shot(win, 'before.png')
    insert_models(qtbot, win)
    move_and_delete(qtbot, win)
    step = pause_and_step_100(qtbot, win)
    check_screenshot(qtbot, win, before, origin)
    save_world(win, step)
    win.close()
