"""The 3D view widget on a scene of our own (no ROS): it draws the models with the renderer,
the mouse moves the camera as in Gazebo, a click selects the model under the cursor and the
selection is highlighted. In-process Qt (pytest-qt), offscreen when there is no display."""
import os

if not os.environ.get('DISPLAY'):
    os.environ.setdefault('QT_QPA_PLATFORM', 'offscreen')

import numpy as np                      # noqa: E402
import pytest                           # noqa: E402
from PyQt5 import QtCore, QtGui, QtWidgets   # noqa: E402

from ode_sim.description.transforms import Pose   # noqa: E402
from ode_sim_gui.scene import SceneModel           # noqa: E402
from ode_sim_gui.view import View3D                # noqa: E402

WORLD = """<sdf version="1.6"><world name="default">
<scene><ambient>0.4 0.4 0.4 1</ambient><background>0.2 0.3 0.9 1</background></scene>
<light name="sun" type="directional"><direction>-0.5 0.1 -0.9</direction>
  <diffuse>0.8 0.8 0.8 1</diffuse></light>
<model name="red_box"><pose>0 0 0.5 0 0 0</pose><link name="link">
  <collision name="c"><geometry><box><size>1 1 1</size></box></geometry></collision>
  <visual name="v"><geometry><box><size>1 1 1</size></box></geometry>
   <material><ambient>1 0 0 1</ambient><diffuse>1 0 0 1</diffuse></material></visual>
</link></model>
<model name="green_ball"><pose>0 3 0.5 0 0 0</pose><link name="link">
  <collision name="c"><geometry><sphere><radius>0.5</radius></sphere></geometry></collision>
  <visual name="v"><geometry><sphere><radius>0.5</radius></sphere></geometry>
   <material><ambient>0 1 0 1</ambient><diffuse>0 1 0 1</diffuse></material></visual>
</link></model>
</world></sdf>"""


def red(rgb):
    r, g, b = (rgb[..., i].astype(int) for i in range(3))
    return (r > 100) & (g < 0.4 * r) & (b < 0.4 * r)


def orange(rgb):
    r, g, b = (rgb[..., i].astype(int) for i in range(3))
    return (r > 200) & (g > 100) & (g < 200) & (b < 80)


@pytest.fixture
def view(qtbot):
    scene = SceneModel()
    scene.update_world(WORLD)
    v = View3D(scene)
    v.resize(640, 480)
    qtbot.addWidget(v)
    v.show()
    qtbot.waitExposed(v)
    v.camera.look_at((6, 0, 3), (0, 0, 0.5))
    yield v
    v.release()


def drag(widget, button, points, modifiers=QtCore.Qt.NoModifier):
    """A mouse drag through `points` as the X server delivers it (QTest's mouseMove carries no
    pressed buttons)."""
    send = QtWidgets.QApplication.sendEvent
    E = QtGui.QMouseEvent
    p0 = QtCore.QPointF(*points[0])
    send(widget, E(E.MouseButtonPress, p0, button, button, modifiers))
    for p in points[1:]:
        send(widget, E(E.MouseMove, QtCore.QPointF(*p), QtCore.Qt.NoButton, button, modifiers))
    send(widget, E(E.MouseButtonRelease, QtCore.QPointF(*points[-1]), button,
                   QtCore.Qt.NoButton, modifiers))


def frame(v):
    v.render_now()
    return v.last_rgb().copy()


def test_draws_models_sky_and_follows_poses(view):
    rgb = frame(view)
    assert rgb.shape == (480, 640, 3)
    x, y = (int(round(c)) for c in view.camera.project((0, 0, 0.5)))
    assert red(rgb[y - 5:y + 5, x - 5:x + 5]).all()           # the box, where it is
    assert np.abs(rgb[5, 320].astype(int) - (51, 77, 230)).max() <= 1   # the sky colour
    assert red(rgb).sum() > 3000
    # a new pose from the simulator moves it: the box leaves the centre
    view.scene.set_poses({'red_box::link': Pose((0, -3, 0.5))}, {})
    rgb = frame(view)
    assert not red(rgb[y - 5:y + 5, x - 5:x + 5]).any()
    x2, y2 = (int(round(c)) for c in view.camera.project((0, -3, 0.5)))
    assert red(rgb[y2 - 3:y2 + 3, x2 - 3:x2 + 3]).all()


def test_mouse_orbit_pan_zoom(view, qtbot):
    yaw, focus, dist = view.camera.yaw, view.camera.focus.copy(), view.camera.distance
    drag(view, QtCore.Qt.LeftButton, [(x, 200) for x in range(300, 365, 5)])
    assert view.camera.yaw != pytest.approx(yaw)
    assert np.allclose(view.camera.focus, focus)
    yaw = view.camera.yaw
    # shift + left drag pans
    drag(view, QtCore.Qt.LeftButton, [(x, 200) for x in range(300, 365, 5)],
         QtCore.Qt.ShiftModifier)
    assert view.camera.yaw == pytest.approx(yaw)
    assert not np.allclose(view.camera.focus, focus)
    focus = view.camera.focus.copy()
    drag(view, QtCore.Qt.MiddleButton, [(300, y) for y in range(200, 265, 5)])
    assert view.camera.yaw == pytest.approx(yaw)
    assert view.camera.focus[2] > focus[2]               # dragged down: the camera went up
    dist = view.camera.distance
    ev = QtGui.QWheelEvent(QtCore.QPointF(100, 100), QtCore.QPointF(100, 100), QtCore.QPoint(),
                           QtCore.QPoint(0, 240), QtCore.Qt.NoButton, QtCore.Qt.NoModifier,
                           QtCore.Qt.NoScrollPhase, False)
    QtWidgets.QApplication.sendEvent(view, ev)
    assert view.camera.distance == pytest.approx(dist * 0.64)
    view.reset_view()
    assert np.allclose(view.camera.eye(), (5, -5, 2))


def test_click_selects_and_highlights(view, qtbot):
    before = orange(frame(view)).sum()
    x, y = (int(round(c)) for c in view.camera.project((0, 3, 0.5)))
    with qtbot.waitSignal(view.selected) as sig:
        qtbot.mouseClick(view, QtCore.Qt.LeftButton, pos=QtCore.QPoint(x, y))
    assert sig.args == ['green_ball']
    view.scene.selected = 'green_ball'
    view.scene_changed()
    after = orange(frame(view)).sum()
    assert after > before + 200            # the selection box
    with qtbot.waitSignal(view.selected) as sig:
        qtbot.mouseClick(view, QtCore.Qt.LeftButton, pos=QtCore.QPoint(5, 5))
    assert sig.args == [None]


def test_place_mode_reports_the_ground_point(view, qtbot):
    view.mode = 'place'
    x, y = view.camera.project((1.0, -2.0, 0.0))
    with qtbot.waitSignal(view.ground_clicked) as sig:
        qtbot.mouseClick(view, QtCore.Qt.LeftButton, pos=QtCore.QPoint(int(round(x)), int(round(y))))
    assert sig.args[0] == pytest.approx(1.0, abs=0.05)
    assert sig.args[1] == pytest.approx(-2.0, abs=0.05)


def test_half_resolution_while_moving_then_full(view, qtbot):
    view.full_frame_cost = 0.0                     # as if full frames were cheap
    view.repaint()
    assert view.last_rgb().shape == (480, 640, 3)
    view.full_frame_cost = 1.0                     # as if a full frame took a second
    view.camera.orbit(20, 0)
    view.repaint()                                 # moving: half the pixels each way
    assert view.last_rgb().shape == (240, 320, 3)
    assert red(view.last_rgb()).sum() > 700        # the same scene
    qtbot.waitUntil(lambda: view.last_rgb().shape == (480, 640, 3), timeout=5000)
    view.full_frame_cost = 0.001                   # cheap frames: always full resolution
    view.camera.orbit(20, 0)
    view.repaint()
    assert view.last_rgb().shape == (480, 640, 3)


def test_moving_models_over_the_cached_still_scene(view):
    """Camera still, the red box moving: after a full frame and one that caches the still
    shapes, frames are drawn over the cache at full resolution even when full frames are slow,
    and they are the frames an uncached renderer draws."""
    view.full_frame_cost = 0.0
    view.repaint()                                   # full frame: this camera
    view.full_frame_cost = 1.0                       # as if a full frame took a second
    r = view._renderers[1.0]
    for i in range(4):
        view.scene.set_poses({'red_box::link': Pose((0, -0.5 * i, 0.5))}, {})
        view.repaint()
        assert view.last_rgb().shape == (480, 640, 3)    # the camera is still: full size
    assert r.cached
    got = view.last_rgb().copy()
    x, y = (int(round(c)) for c in view.camera.project((0, -1.5, 0.5)))
    assert red(got[y - 3:y + 3, x - 3:x + 3]).all()      # where the box is now
    x0, y0 = (int(round(c)) for c in view.camera.project((0, 0.45, 0.5)))
    assert not red(got[y0 - 3:y0 + 3, x0 - 3:x0 + 3]).any()   # not where it was
    view.scene_changed()                             # a new renderer state: no cache
    view.render_now()
    assert not r.cached
    fresh = view.last_rgb().astype(int)
    assert (np.abs(fresh - got).max(axis=2) > 0).sum() <= 20  # the same frame (z ties aside)
    view.full_frame_cost = 1.0
    view.camera.orbit(20, 0)
    view.repaint()                                   # the camera moves: half resolution
    assert view.last_rgb().shape == (240, 320, 3)
