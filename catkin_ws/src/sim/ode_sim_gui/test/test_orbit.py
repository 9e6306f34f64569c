"""The view's camera maths (no ROS, no Qt, no GL)."""
import math

import numpy as np
import pytest

from ode_sim_gui.orbit import OrbitCamera, PITCH_LIMIT


def cam():
    return OrbitCamera(1280, 720, math.radians(60))


def test_reset_is_gazebos_default_camera():
    c = cam()
    assert np.allclose(c.eye(), (5, -5, 2))
    assert np.allclose(c.focus, (0, 0, 0))
    assert c.yaw == pytest.approx(3 * math.pi / 4)
    assert c.pitch == pytest.approx(math.asin(2 / math.sqrt(54)))
    assert c.project((0, 0, 0)) == pytest.approx((640, 360))
    c.orbit(100, 30)
    c.pan(40, -10)
    c.zoom(3, 10, 10)
    c.reset()
    assert np.allclose(c.eye(), (5, -5, 2))


def test_pose_axes():
    c = cam()
    c.look_at((0, 0, 1), (10, 0, 1))
    rot = c.pose().rotation()
    assert np.allclose(rot[:, 0], (1, 0, 0))    # X forward
    assert np.allclose(rot[:, 2], (0, 0, 1))    # Z up
    # a point to the left (+Y) is drawn left of the centre, one above it higher up
    x, y = c.project((10, 1, 1))
    assert x < 640 and y == pytest.approx(360)
    x, y = c.project((10, 0, 2))
    assert y < 360 and x == pytest.approx(640)
    assert c.project((-10, 0, 1)) is None


@pytest.mark.parametrize('px', [(0, 0), (1279, 719), (200, 500), (640, 360)])
def test_ray_and_project_agree(px):
    c = cam()
    o, d = c.ray(*px)
    assert np.allclose(o, c.eye())
    assert np.linalg.norm(d) == pytest.approx(1)
    assert c.project(o + 7.3 * d) == pytest.approx(px)


def test_ground_point():
    c = cam()
    p = c.ground_point(640, 360)
    assert np.allclose(p, (0, 0, 0), atol=1e-9)
    p = c.ground_point(300, 600)
    assert p[2] == pytest.approx(0)
    assert c.project(p) == pytest.approx((300, 600))
    assert c.ground_point(640, 0) is None            # above the horizon
    assert c.ground_point(640, 500, z=0.5)[2] == pytest.approx(0.5)


def test_orbit_keeps_focus_and_distance_and_clamps_pitch():
    c = cam()
    d0 = c.distance
    c.orbit(157, 0)
    assert c.yaw == pytest.approx(3 * math.pi / 4 - 1.57)
    assert np.allclose(c.focus, 0) and c.distance == pytest.approx(d0)
    assert c.project((0, 0, 0)) == pytest.approx((640, 360))
    c.orbit(0, 10000)
    assert c.pitch == pytest.approx(PITCH_LIMIT)
    c.orbit(0, -20000)
    assert c.pitch == pytest.approx(-PITCH_LIMIT)


def test_pan_moves_the_focus_plane_with_the_cursor():
    c = cam()
    fwd = c.forward()
    # a point on the plane through the focus, facing the camera
    o, d = c.ray(400, 300)
    p = o + d * (c.distance / np.dot(d, fwd))
    c.pan(55, -23)
    assert c.project(p) == pytest.approx((455, 277))
    assert c.distance == pytest.approx(math.sqrt(54))


@pytest.mark.parametrize('notches', [1, 3, -2])
def test_zoom_towards_the_cursor(notches):
    c = cam()
    fwd = c.forward()
    o, d = c.ray(900, 200)
    p = o + d * (c.distance / np.dot(d, fwd))
    d0 = c.distance
    c.zoom(notches, 900, 200)
    assert c.distance == pytest.approx(d0 * 0.8 ** notches)
    assert c.project(p) == pytest.approx((900, 200))
    assert np.allclose(c.forward(), fwd)


def test_zoom_limits_and_centre():
    c = cam()
    c.zoom(100)
    assert c.distance == pytest.approx(0.05)
    assert c.project((0, 0, 0)) == pytest.approx((640, 360))
    c.zoom(-1000)
    assert c.distance == pytest.approx(1000)


def test_frame_and_bad_sizes():
    c = cam()
    c.frame((3, 4, 0.5), 1.0)
    assert np.allclose(c.focus, (3, 4, 0.5))
    assert c.project((3, 4, 0.5)) == pytest.approx((640, 360))
    with pytest.raises(ValueError):
        c.resize(0, 10)
    with pytest.raises(ValueError):
        c.look_at((1, 1, 1), (1, 1, 1))
