"""ode_sim.render: offscreen OpenGL camera images checked against the pinhole model.

No roscore, no display: Mesa's EGL (llvmpipe) renders offscreen.
"""
import math
import threading

import numpy as np
import pytest

from ode_sim.description.model import Geometry, Light, ModelError
from ode_sim.engine.render import Renderer, camera_info_matrix, focal_length
from ode_sim.engine.scene import ShapeInstance
from ode_sim.engine.tessellate import tessellate
from ode_sim.description.transforms import Pose

W, H, HFOV = 640, 480, 1.047
BG = (0.7, 0.7, 0.7, 1.0)
BG_RGB = np.array([178, 178, 178])          # round(0.7 * 255)
RED = (1.0, 0.0, 0.0, 1.0)


def shape(name, geom, xyz=(0, 0, 0), rpy=(0, 0, 0), color=RED):
    return ShapeInstance('%s::link::visual' % name, name, 'link', geom, color=color,
                         static_pose=Pose.from_xyz_rpy(xyz, rpy))


def box(size=(1, 1, 1)):
    return Geometry('box', size=size)


def red_mask(rgb):
    r, g, b = (rgb[..., i].astype(int) for i in range(3))
    return (r > g + 50) & (r > b + 50)


def background_mask(rgb):
    return np.all(rgb == BG_RGB, axis=-1)


def pinhole_square(width, height, hfov, dist, half):
    """Pixel mask of an axis-aligned square (half size `half`) facing the camera at `dist`
    on the optical axis, and the mask of pixels within 1.5 px of its edges."""
    f = focal_length(width, hfov)
    h = f * half / dist
    u = np.arange(width) + 0.5 - width / 2.0           # pixel centres, 0 at the image centre
    v = np.arange(height) + 0.5 - height / 2.0
    du = np.abs(u)[None, :] - h
    dv = np.abs(v)[:, None] - h
    inside = (du < 0) & (dv < 0)
    edge = (np.abs(du) <= 1.5) & (dv <= 1.5) | (np.abs(dv) <= 1.5) & (du <= 1.5)
    return inside, edge


@pytest.fixture(scope='module')
def cam():
    return Renderer(W, H, HFOV, depth=True)


def test_camera_info_matches_gazebo_defaults():
    K, P = camera_info_matrix(640, 480, 1.047)
    f = 640 / (2 * math.tan(1.047 / 2))
    assert K == pytest.approx(np.array([[f, 0, 320.5], [0, f, 240.5], [0, 0, 1]]))
    assert P == pytest.approx(np.array([[f, 0, 320.5, 0], [0, f, 240.5, 0], [0, 0, 1, 0]]))
    K, P = camera_info_matrix(320, 240, 1.3, cx=100, cy=90, focal=200, hack_baseline=0.07)
    assert (K[0, 0], K[1, 1], K[0, 2], K[1, 2]) == (200, 200, 100, 90)
    assert P[0, 3] == pytest.approx(-14.0)


@pytest.mark.parametrize('camera_pose, box_pose', [
    (Pose(), Pose((3, 0, 0))),
    # camera elsewhere, looking along world +Y (yaw 90 deg): the same picture
    (Pose.from_xyz_rpy((10, 5, 2), (0, 0, math.pi / 2)), Pose.from_xyz_rpy((10, 8, 2), (0, 0, 0.0))),
])
def test_box_fills_the_pinhole_square(cam, camera_pose, box_pose):
    s = ShapeInstance('b::l::v', 'b', 'l', box(), color=RED, static_pose=box_pose)
    cam.set_scene([s], [Light('sun')], background=BG)
    rgb, depth = cam.render(camera_pose)
    assert rgb.shape == (H, W, 3) and rgb.dtype == np.uint8
    inside, edge = pinhole_square(W, H, HFOV, 2.5, 0.5)     # the front face at 2.5 m
    red = red_mask(rgb)
    core = inside & ~edge
    assert red[core].mean() >= 0.98
    assert background_mask(rgb)[~inside & ~edge].all()
    # every pixel agrees with the pinhole prediction except within 1.5 px of the edges
    wrong = red != inside
    assert not (wrong & ~edge).any(), np.argwhere(wrong & ~edge)[:5]
    # depth: distance along the optical axis, also off the axis on the front face
    assert depth.dtype == np.float32 and depth.shape == (H, W)
    assert depth[H // 2, W // 2] == pytest.approx(2.5, rel=0.005)
    assert depth[H // 2 - 100, W // 2 + 100] == pytest.approx(2.5, rel=0.005)
    assert np.isinf(depth[~inside & ~edge]).all() and (depth[~inside & ~edge] > 0).all()


def test_axes_left_is_plus_y_and_up_is_plus_z(cam):
    f = focal_length(W, HFOV)
    ball = shape('ball', Geometry('sphere', radius=0.3), (3, 1, 0), color=(0, 1, 0, 1))
    top = shape('top', box(), (3, 0, 1.0))
    cam.set_scene([ball, top], [Light('sun')], background=BG)
    rgb, _ = cam.render(Pose())
    green = (rgb[..., 1].astype(int) > rgb[..., 0] + 50) & (rgb[..., 1].astype(int) > rgb[..., 2] + 50)
    rows, cols = np.nonzero(green)
    assert cols.max() < W // 2                                   # on the left
    assert cols.mean() == pytest.approx(W / 2 - f * 1 / 3, abs=4)
    assert rows.mean() == pytest.approx(H / 2, abs=2)
    red = red_mask(rgb)
    rows = np.nonzero(red[:, W // 2])[0]
    assert rows.min() == 0                                       # in the top rows
    # seen from below: the lowest visible edge is the bottom face's far edge (x 3.5, z 0.5)
    assert rows.max() + 0.5 == pytest.approx(H / 2 - f * 0.5 / 3.5, abs=1.5)


def test_cylinder_axis_is_local_z(cam):
    f = focal_length(W, HFOV)
    cyl = shape('cyl', Geometry('cylinder', radius=0.5, length=2.0), (3, 0, 0))
    cam.set_scene([cyl], [Light('sun')], background=BG)
    rgb, depth = cam.render(Pose())
    red = red_mask(rgb)
    cols = np.nonzero(red[H // 2])[0]
    half_w = f * math.tan(math.asin(0.5 / 3))                    # tangent rays
    assert (cols.max() - cols.min() + 1) / 2 == pytest.approx(half_w, abs=2)
    rows = np.nonzero(red[:, W // 2])[0]
    assert H / 2 - rows.min() == pytest.approx(f * 1.0 / 2.5, abs=2)   # cap's near edge
    assert depth[H // 2, W // 2] == pytest.approx(2.5, rel=0.005)


def test_plane_below_the_camera_fills_the_lower_half(cam):
    f = focal_length(W, HFOV)
    floor = shape('ground', Geometry('plane', plane_size=(100, 100)), (0, 0, 0), color=(0, 0, 1, 1))
    cam.set_scene([floor], [Light('sun')], background=BG)
    rgb, depth = cam.render(Pose((0, 0, 1)))
    blue = (rgb[..., 2].astype(int) > rgb[..., 0] + 50)
    horizon = H / 2 + f * 1 / 50                                 # the plane ends 50 m ahead
    assert blue[int(horizon) + 2:].all()
    assert not blue[:int(horizon) - 1].any()
    # a row below the centre looks at the floor: depth = height * f / (row offset)
    row = H // 2 + 100
    assert depth[row, W // 2] == pytest.approx(f / (row + 0.5 - H / 2), rel=0.005)


def test_face_towards_the_light_is_brighter(cam):
    cube = shape('cube', box(), (3, 0, 0), rpy=(0, 0, math.pi / 4))   # two faces visible
    # light shining towards -Y: it comes from the left (+Y) side
    cam.set_scene([cube], [Light('sun', direction=(0, -1, 0))], ambient=(0.2, 0.2, 0.2, 1),
                  background=BG)
    rgb, _ = cam.render(Pose())
    row = rgb[H // 2, :, 0].astype(int)
    left, right = row[W // 2 - 40], row[W // 2 + 40]
    assert left > right + 60
    assert right == pytest.approx(0.2 * 255, abs=3)               # ambient only
    # the same face lit from behind the camera vs from behind the box
    front = shape('front', box(), (3, 0, 0))
    cam.set_scene([front], [Light('sun', direction=(1, 0, 0))], background=BG)
    lit = cam.render(Pose())[0][H // 2, W // 2, 0]
    cam.set_scene([front], [Light('sun', direction=(-1, 0, 0))], background=BG)
    unlit = cam.render(Pose())[0][H // 2, W // 2, 0]
    assert int(lit) > int(unlit) + 100


def test_point_light_and_no_lights(cam):
    front = shape('front', box(), (3, 0, 0))
    cam.set_scene([front], [Light('bulb', type='point', pose=Pose((0, 0, 0)))], background=BG)
    lit = cam.render(Pose())[0][H // 2, W // 2, 0]
    cam.set_scene([front], [], ambient=(0.5, 0.5, 0.5, 1), background=BG)
    flat = cam.render(Pose())[0]
    assert int(lit) > 200
    assert flat[H // 2, W // 2, 0] == pytest.approx(128, abs=2)


def test_mesh_renders_like_the_primitive(cam):
    pos, _, idx = tessellate(box())
    # the cube as a mesh with shared corners (8 vertices, 12 faces)
    verts, inv = np.unique(np.round(pos, 6), axis=0, return_inverse=True)
    faces = inv.reshape(-1)[idx]
    mesh = Geometry('mesh', uri='test://cube', vertices=verts, faces=faces)
    assert len(verts) == 8 and len(faces) == 12
    cam.set_scene([shape('m', mesh, (3, 0, 0))], [Light('sun')], background=BG)
    rgb_mesh, depth_mesh = cam.render(Pose())
    cam.set_scene([shape('b', box(), (3, 0, 0))], [Light('sun')], background=BG)
    rgb_box, depth_box = cam.render(Pose())
    assert red_mask(rgb_mesh).sum() > 0.1 * W * H
    assert (red_mask(rgb_mesh) == red_mask(rgb_box)).all()
    assert np.abs(rgb_mesh.astype(int) - rgb_box).max() <= 2
    assert np.allclose(depth_mesh, depth_box)


def test_set_scene_again_adds_and_removes(cam):
    red = shape('red', box(), (3, 0, 0))
    green = shape('green', Geometry('sphere', radius=0.4), (3, 0, 0), color=(0, 1, 0, 1))
    cam.set_scene([red], [Light('sun')], background=BG)
    assert red_mask(cam.render(Pose())[0])[H // 2, W // 2]
    cam.set_scene([green], [Light('sun')], background=BG)         # red removed, green added
    rgb, depth = cam.render(Pose())
    assert not red_mask(rgb).any()
    assert rgb[H // 2, W // 2, 1] > rgb[H // 2, W // 2, 0] + 50
    assert depth[H // 2, W // 2] == pytest.approx(2.6, rel=0.005)
    assert len(cam._meshes) == 1                                  # the box's buffers freed
    cam.set_scene([red, green], [Light('sun')], background=BG)    # both: the box is in front
    assert red_mask(cam.render(Pose())[0])[H // 2, W // 2]
    assert len(cam._meshes) == 2
    cam.set_scene([], background=(0, 0, 1, 1))
    rgb, depth = cam.render(Pose())
    assert (rgb == [0, 0, 255]).all() and np.isinf(depth).all()


def test_moving_shape_follows_its_link():
    pose = [Pose((3, 0, 0))]
    s = ShapeInstance('mv::l::v', 'mv', 'l', box(), color=RED, link_pose=lambda: pose[0])
    r = Renderer(160, 120, HFOV)
    r.set_scene([s])
    assert red_mask(r.render(Pose())[0])[60, 80]
    pose[0] = Pose((3, 5, 0))                                     # out of view
    rgb, depth = r.render(Pose())
    assert depth is None and not red_mask(rgb).any()
    r.release()


def test_two_renderers_of_different_sizes():
    small = Renderer(320, 240, HFOV, depth=True)
    big = Renderer(800, 600, 1.2)
    scene = [shape('b', box(), (3, 0, 0))]
    small.set_scene(scene, [Light('sun')], background=BG)
    big.set_scene(scene, [Light('sun')], background=BG)
    for _ in range(2):                                            # interleaved
        for r in (small, big):
            rgb, _ = r.render(Pose())
            assert rgb.shape == (r.height, r.width, 3)
            inside, edge = pinhole_square(r.width, r.height, r.hfov, 2.5, 0.5)
            assert not ((red_mask(rgb) != inside) & ~edge).any()
    small.release()
    big.release()
    with pytest.raises(ModelError):
        big.render(Pose())


def test_beyond_far_is_inf_and_background():
    r = Renderer(160, 120, HFOV, near=0.1, far=10.0, depth=True)
    r.set_scene([shape('far', box((1, 20, 20)), (12, 0, 0)), shape('near', box(), (3, 0, 0))],
                background=BG)
    rgb, depth = r.render(Pose())
    assert depth[60, 80] == pytest.approx(2.5, rel=0.005)
    assert np.isinf(depth[5, 5]) and (rgb[5, 5] == BG_RGB).all()
    r.release()


def test_render_from_another_thread(cam):
    cam.set_scene([shape('b', box(), (3, 0, 0))], [Light('sun')], background=BG)
    out = []
    t = threading.Thread(target=lambda: out.append(cam.render(Pose())))
    t.start()
    t.join(30)
    assert out and red_mask(out[0][0])[H // 2, W // 2]
    assert out[0][1][H // 2, W // 2] == pytest.approx(2.5, rel=0.005)


@pytest.mark.parametrize('geom, message', [
    (Geometry('box', size=(0, 1, 1)), 'bad::link::visual: box geometry: box size must be 3 positive'),
    (Geometry('sphere', radius=-1), 'sphere radius must be positive'),
    (Geometry('cylinder', radius=1), 'cylinder radius and length must be positive'),
    (Geometry('mesh', uri='model://x/a.stl'), "mesh 'model://x/a.stl' has no vertices/faces"),
    (Geometry('mesh', vertices=np.zeros((3, 3)), faces=np.array([[0, 1, 5]])), 'out of range'),
    (Geometry('plane', normal=(0, 0, 0)), 'plane normal [0, 0, 0] is not a direction'),
    (Geometry('capsule'), "unknown geometry kind 'capsule'"),
])
def test_bad_geometry_is_one_clear_error(cam, geom, message):
    with pytest.raises(ModelError) as e:
        cam.set_scene([shape('bad', geom)])
    assert message in str(e.value) and '\n' not in str(e.value)


def test_bad_arguments():
    with pytest.raises(ModelError, match='size must be positive'):
        Renderer(0, 480, HFOV)
    with pytest.raises(ModelError, match='horizontal_fov'):
        Renderer(640, 480, 3.2)
    with pytest.raises(ModelError, match='near'):
        Renderer(640, 480, HFOV, near=5, far=1)
    r = Renderer(16, 12, HFOV)
    with pytest.raises(ModelError, match='colour'):
        r.set_scene([shape('c', box(), color=(1, 0))])
    with pytest.raises(ModelError, match="light 'l': direction"):
        r.set_scene([], [Light('l', direction=(0, 0, 0))])
    r.release()


def test_no_egl_is_one_clear_error(tmp_path):
    # libglvnd finds no EGL vendor: the context cannot be made
    import os
    import subprocess
    import sys
    env = dict(os.environ, __EGL_VENDOR_LIBRARY_FILENAMES=str(tmp_path / 'none.json'))
    code = ('from ode_sim.engine.render import Renderer\n'
            'from ode_sim.description.model import ModelError\n'
            'try:\n    Renderer(8, 8, 1.0)\n'
            'except ModelError as e:\n    print("ERR", e)\n')
    out = subprocess.run([sys.executable, '-c', code], env=env, capture_output=True, text=True,
                         timeout=60)
    assert out.returncode == 0, out.stderr
    line = out.stdout.strip()
    assert line.startswith('ERR ode_sim.render: cannot create an offscreen OpenGL')
    assert 'libegl-mesa0' in line and '\n' not in line


def test_camera_inside_its_own_box_sees_out():
    """Back faces are culled as in Gazebo: the textbook's camera sits in the middle of a 5 cm
    black cube with a 2 cm near clip and still sees the red box in front of it."""
    r = Renderer(160, 120, HFOV, near=0.02, depth=False)
    housing = shape('camera', box((0.05, 0.05, 0.05)), color=(0, 0, 0, 1))
    r.set_scene([housing, shape('target', box(), xyz=(3, 0, 0))])
    rgb, _ = r.render(Pose())
    assert red_mask(rgb)[50:70, 70:90].all()
    assert not (rgb.max(axis=-1) == 0).all()
