"""The compiled ray caster (RayCaster(core='compiled'): engine/raycore.py + core/raycast.cpp)
against the NumPy one it replaces (core='python', the reference): the same distances (to
1e-9 m), the same shape hit (or, where faces coincide, one at that distance), the same inf
where nothing is hit, on the office world with the space scanner (its lidar, its own shapes
excluded or not), on a scene with every primitive and meshes (static and moving) at many poses,
and on rays grazing edges, corners and faces."""
import math
import os
import shutil
import subprocess

import numpy as np
import pytest

from ode_sim.description import meshgen, sdf, urdf
from ode_sim.description.model import Geometry, ModelError, Physics, World
from ode_sim.description.transforms import Pose
from ode_sim.engine import _core
from ode_sim.engine.laser import LaserModel
from ode_sim.engine.physics import PhysicsWorld
from ode_sim.engine.raycast import RayCaster
from ode_sim.engine.rayprims import Posing
from ode_sim.engine.scene import ShapeInstance
from ode_sim.ros.plugins.base import PluginContext

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.abspath(os.path.join(HERE, '..', '..', '..'))
TOL = 1e-9


def both(shapes):
    return RayCaster(shapes, core='python'), RayCaster(shapes, core='compiled')


def excluded_by(exclude, shape):
    if exclude is None:
        return False
    return exclude(shape) if callable(exclude) else (shape.model, shape.link) in exclude


def agree(casters, origins, dirs, max_range, exclude=None, min_range=0.0):
    """Cast with both cores; assert they agree; return (t, shape index) of the compiled one.
    Where two shapes' faces coincide (a sofa's seat and arm boxes of one link), the cores may
    name different ones, differing in the last bit: the compiled core's shape must then lie at
    the reference's distance, by the reference's own cast at that shape alone."""
    ref, comp = casters
    t0, k0 = ref.cast_hits(origins, dirs, max_range, exclude, min_range)
    t1, k1 = comp.cast_hits(origins, dirs, max_range, exclude, min_range)
    assert t1.shape == t0.shape and k1.dtype == k0.dtype
    np.testing.assert_array_equal(np.isposinf(t1), np.isposinf(t0))
    assert not np.isnan(t0).any() and not np.isnan(t1).any()
    fin = np.isfinite(t0)
    np.testing.assert_allclose(t1[fin], t0[fin], atol=TOL, rtol=0)
    np.testing.assert_array_equal(k1 >= 0, fin)
    o = np.asarray(origins, dtype=float)
    for r in np.nonzero(k1 != k0)[0]:
        shape = ref.shapes[k1[r]]
        assert not excluded_by(exclude, shape), (r, shape.key)
        alone, hit = ref.cast_hits(o if o.ndim == 1 else o[r:r + 1], dirs[r:r + 1], max_range,
                                   lambda s, keep=shape: s is not keep, min_range)
        assert hit[0] == k1[r] and abs(alone[0] - t0[r]) <= TOL, (r, shape.key, alone[0], t0[r])
    return t1, k1


def fan(n=360, pitch=0.0):
    yaw = 2 * math.pi * np.arange(n) / n - math.pi
    return np.stack([np.cos(pitch) * np.cos(yaw), np.cos(pitch) * np.sin(yaw),
                     np.full(n, math.sin(pitch))], axis=1)


def random_dirs(rng, n, flat=0.5):
    d = rng.normal(size=(n, 3))
    d[:, 2] *= flat
    return d / np.linalg.norm(d, axis=1)[:, None]


# ------------------------------------------------------------------------------------------
# the office world with the space scanner, on a real PhysicsWorld (dynamic furniture, the
# robot's links read from their ODE bodies)

@pytest.fixture(scope='module')
def office():
    world = sdf.load_world(os.path.join(SRC, 'sim', 'ode_sim', 'worlds', 'office.world'))
    rel = 'space_scanner/space_scanner_simulation/urdf/chassi_bot.urdf.xacro'
    exe = shutil.which('xacro')
    assert exe is not None, 'xacro is not on PATH: the workspace is not built or not sourced'
    out = subprocess.run([exe, os.path.join(SRC, rel)], capture_output=True, text=True,
                         timeout=60)
    assert out.returncode == 0, out.stderr
    # quickStep's constraint order comes from ODE's process-wide random generator: seeded, the
    # furniture settles the same way whatever ran before in this process (a pytest worker)
    _core.set_random_seed(1)
    pw = PhysicsWorld(world.physics, world.gravity)
    for m in world.models:
        pw.add_model(m)
    robot = urdf.parse_urdf(out.stdout, os.path.join(SRC, rel), 'robot')
    robot.pose = Pose.from_xyz_rpy((0.5, 0.3, 0.05), (0, 0, 0.4))
    m = pw.add_model(robot)
    for j in m.joints.values():
        if j.hinge:
            j.set_velocity(3.0, fmax=5.0)
    pw.step(300)                    # the robot drives off: its links are posed by ODE
    sensor = [s for link in robot.links for s in link.sensors if s.type == 'ray'][0]
    return pw, m, sensor


def test_office_robot_lidar_scans_agree(office):
    pw, m, sensor = office
    shapes = pw.collision_shapes()
    casters = both(shapes)
    link = m.links[sensor.link] if sensor.link in m.links else \
        [lk for lk in m.links.values() if sensor.link in lk.desc.lumped][0]
    pose = link.frame_pose(sensor.link) * sensor.pose
    own = {('robot', link.name)}
    scans = []
    for caster in casters:
        laser = LaserModel(sensor, rng=np.random.default_rng(5))
        scans.append(laser.scan(caster, pose, own))
        dirs = pose.rotate(laser.directions)
        for exclude in (own, None):
            for min_range in (0.0, laser.range_min):
                t, k = agree(casters, pose.p, dirs, laser.range_max, exclude, min_range)
                assert np.isfinite(t).sum() > 300      # walls all around within 12 m
    (r0, i0), (r1, i1) = scans
    np.testing.assert_array_equal(np.isinf(r1), np.isinf(r0))
    np.testing.assert_allclose(r1[np.isfinite(r0)], r0[np.isfinite(r0)], atol=TOL, rtol=0)
    np.testing.assert_array_equal(i1, i0)
    # from the robot's base, with range_min 0, its own shapes are hit unless excluded
    base = m.links['base_link'].pose() if 'base_link' in m.links else m.pose()
    t, k = agree(casters, base.p, fan(), 12.0)
    assert {shapes[j].model for j in k if j >= 0} == {'robot'}
    t, k = agree(casters, base.p, fan(), 12.0, exclude=lambda s: s.model == 'robot')
    assert 'robot' not in {shapes[j].model for j in k if j >= 0}


def test_office_many_poses_agree(office):
    pw, m, _ = office
    shapes = pw.collision_shapes()
    casters = both(shapes)
    rng = np.random.default_rng(11)
    robot = {('robot', name) for name in m.links}
    hits = 0
    for i in range(40):
        c = np.array([rng.uniform(-9, 9), rng.uniform(-6, 6), rng.uniform(0.02, 1.6)])
        pose = Pose.from_xyz_rpy(c, (rng.normal(0, 0.1), rng.normal(0, 0.1),
                                     rng.uniform(-math.pi, math.pi)))
        dirs = pose.rotate(fan(360, pitch=rng.choice([0.0, -0.2, 0.15])))
        exclude = robot if i % 2 else None
        min_range = (0.0, 0.12, 0.5)[i % 3]
        t, _ = agree(casters, c, dirs, (3.5, 12.0, np.inf)[i % 3], exclude, min_range)
        hits += int(np.isfinite(t).sum())
        # the same rays from nearby origins of their own (the per-ray path)
        origins = c + rng.normal(0, 0.01, (len(dirs), 3))
        agree(casters, origins, dirs, 12.0, exclude, min_range)
    assert hits > 6000


def test_simulated_links_are_posed_from_their_bodies(office):
    """rayprims.Posing reads SimLink poses from the ODE bodies in one batch: the same poses
    as ShapeInstance.world_pose() (link.pose() * local)."""
    pw, m, _ = office
    dyn = [s for s in pw.collision_shapes() if not s.static]
    assert any(s.model == 'robot' for s in dyn) and len(dyn) > 20
    posing = Posing(dyn)
    assert len(posing.bodies) == len(posing.calls) and not posing.generic
    rot, pos = posing()
    for s, r, p in zip(dyn, rot, pos):
        w = s.world_pose()
        np.testing.assert_allclose(r, w.rotation(), atol=1e-12)
        np.testing.assert_allclose(p, w.p, atol=1e-12)


# ------------------------------------------------------------------------------------------
# every primitive and meshes, static and on a moving link

def uv_sphere(rx, ry, rz, n_lat=10, n_lon=20):
    part = meshgen.ellipsoid((rx, ry, rz), segments=n_lon, rings=n_lat)
    return part.vertices, part.faces


def box_mesh(size):
    hx, hy, hz = np.asarray(size, dtype=float) / 2.0
    v = np.array([[sx * hx, sy * hy, sz * hz] for sx in (-1, 1) for sy in (-1, 1)
                  for sz in (-1, 1)])
    f = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    return v, f


def static(key, geom, pose, retro=0.0):
    return ShapeInstance(key=key, model=key, link='link', geometry=geom, static_pose=pose,
                         laser_retro=retro)


def moving(key, geom, link, local, name='body'):
    return ShapeInstance(key='mover::%s' % key, model='mover', link=name, geometry=geom,
                         local=local, link_pose=link)


class Mover:
    """A link pose the tests set; ShapeInstance.link_pose is its bound method."""

    def __init__(self):
        self.now = Pose()

    def pose(self):
        return self.now


def mixed_scene(mover):
    rng = np.random.default_rng(2)
    shapes = [static('ground', Geometry('plane', normal=(0, 0, 1)), Pose((0, 0, -0.05))),
              static('ramp', Geometry('plane', normal=(0.3, -0.2, 1.0)), Pose((0, 0, -3.0)))]
    v1, f1 = uv_sphere(0.3, 0.4, 0.5)
    v2, f2 = box_mesh((0.6, 0.3, 0.9))
    for i in range(24):
        xyz = rng.uniform(-4, 4, 3) * (1, 1, 0.2)
        rpy = rng.uniform(-math.pi, math.pi, 3) * (0.3, 0.3, 1)
        pose = Pose.from_xyz_rpy(xyz, rpy)
        kind = i % 6
        if kind == 0:
            g = Geometry('box', size=tuple(rng.uniform(0.1, 1.2, 3)))
        elif kind == 1:
            g = Geometry('sphere', radius=float(rng.uniform(0.1, 0.5)))
        elif kind == 2:
            g = Geometry('cylinder', radius=float(rng.uniform(0.1, 0.5)),
                         length=float(rng.uniform(0.2, 1.5)))
        elif kind == 3:
            g = Geometry('mesh', vertices=v1, faces=f1)
        elif kind == 4:
            g = Geometry('mesh', vertices=v2, faces=f2)
        else:
            g = Geometry('box', size=(2.0, 0.05, 1.0))        # a thin wall
        shapes.append(static('s%d' % i, g, pose, retro=float(i)))
    # the mover: every kind on one link, plus a second link's box and a tilted plane far below
    link = mover.pose
    shapes += [moving('box', Geometry('box', size=(0.4, 0.3, 0.2)), link, Pose((0.0, 0.0, 0.1))),
               moving('wheel', Geometry('cylinder', radius=0.1, length=0.05), link,
                      Pose.from_xyz_rpy((0, 0.2, 0.1), (math.pi / 2, 0, 0))),
               moving('caster', Geometry('sphere', radius=0.05), link, Pose((-0.15, 0, 0.05))),
               moving('hull', Geometry('mesh', vertices=v1 * 0.5, faces=f1), link,
                      Pose.from_xyz_rpy((0.3, 0, 0.3), (0.2, 0.1, 0.3))),
               moving('crate', Geometry('mesh', vertices=v2, faces=f2), link,
                      Pose.from_xyz_rpy((-0.5, 0.4, 0.3), (0, 0, 0.7))),
               moving('floor', Geometry('plane', normal=(0.1, 0.0, 1.0)), link,
                      Pose((0, 0, -5.0)))]
    return shapes


def test_every_primitive_and_meshes_at_many_poses_agree():
    mover = Mover()
    shapes = mixed_scene(mover)
    casters = both(shapes)
    rng = np.random.default_rng(4)
    kinds = set()
    for i in range(60):
        mover.now = Pose.from_xyz_rpy(rng.uniform(-3, 3, 3) * (1, 1, 0.1),
                                      rng.uniform(-math.pi, math.pi, 3) * (0.2, 0.2, 1))
        if i % 4 == 0:                      # from the mover's own body (inside it)
            c = mover.now.p + mover.now.rotate(np.array([0.0, 0.0, 0.1]))
        elif i % 4 == 1:                    # from inside a static shape
            c = shapes[2 + i % 24].world_pose().p
        else:
            c = rng.uniform(-4, 4, 3) * (1, 1, 0.3)
        exclude = (None, {('mover', 'body')}, lambda s: s.geometry.kind == 'mesh',
                   {('s3', 'link'), ('ground', 'link')})[i % 4]
        min_range = (0.0, 0.1, 0.35)[i % 3]
        max_range = (6.0, 2.0, 50.0)[i % 3]    # not inf: far plane hits (km) round apart
        t, k = agree(casters, c, fan(361, pitch=rng.uniform(-0.4, 0.4)), max_range, exclude,
                     min_range)
        kinds |= {shapes[j].geometry.kind for j in k if j >= 0}
        t, k = agree(casters, c, random_dirs(rng, 200), max_range, exclude, min_range)
        kinds |= {shapes[j].geometry.kind for j in k if j >= 0}
        origins = c + rng.normal(0, 0.3, (300, 3))
        t, k = agree(casters, origins, random_dirs(rng, 300), max_range, exclude, min_range)
        kinds |= {shapes[j].geometry.kind for j in k if j >= 0}
    assert kinds == {'box', 'sphere', 'cylinder', 'plane', 'mesh'}
    # the lidar's ranges and intensities (<laser_retro> of the shape hit) are the same too
    laser = {'samples': 720, 'min_angle': -math.pi, 'max_angle': math.pi, 'range_min': 0.12,
             'range_max': 5.0, 'v_samples': 3, 'v_min_angle': -0.2, 'v_max_angle': 0.1}
    out = [LaserModel(laser).scan(c, Pose((0.5, -0.5, 0.2)), {('mover', 'body')})
           for c in casters]
    np.testing.assert_array_equal(out[0][1], out[1][1])
    np.testing.assert_allclose(out[0][0], out[1][0], atol=TOL, rtol=0)
    assert (out[1][1] > 0).sum() > 100


def test_shapes_changed_by_set_shapes_keep_the_core():
    mover = Mover()
    shapes = mixed_scene(mover)
    ref, comp = both(shapes[:10])
    assert comp.core == 'compiled' and ref.core == 'python'
    ref.set_shapes(shapes)
    comp.set_shapes(shapes)
    assert comp.core == 'compiled' and comp.laser_retro()[-1] == 0.0
    agree((ref, comp), np.array([0.3, 0.2, 0.1]), fan(), 8.0)
    assert RayCaster([]).cast_hits([0, 0, 0], fan(8), 5.0)[1].tolist() == [-1] * 8


# ------------------------------------------------------------------------------------------
# grazing rays: exact (dyadic) geometry, so both casters see the very same numbers

def grazing_scene():
    v, f = box_mesh((1.0, 1.0, 1.0))
    hold = Pose((0.0, 4.0, 0.0))
    return [static('box', Geometry('box', size=(1.0, 1.0, 1.0)), Pose((2.0, 0.0, 0.0))),
            static('ball', Geometry('sphere', radius=0.5), Pose((2.0, 2.0, 0.0))),
            static('can', Geometry('cylinder', radius=0.5, length=1.0), Pose((2.0, -2.0, 0.0))),
            static('cube', Geometry('mesh', vertices=v, faces=f), Pose((-2.0, 0.0, 0.0))),
            static('floor', Geometry('plane', normal=(0, 0, 1)), Pose((0.0, 0.0, -0.5))),
            ShapeInstance(key='held::box', model='held', link='link',
                          geometry=Geometry('box', size=(1.0, 1.0, 1.0)), link_pose=lambda: hold),
            ShapeInstance(key='held::cube', model='held', link='link',
                          geometry=Geometry('mesh', vertices=v, faces=f),
                          local=Pose((-4.0, 0.0, 0.0)), link_pose=lambda: hold)]


def test_rays_grazing_edges_corners_and_faces_agree():
    casters = both(grazing_scene())
    offsets = (-0.5 - 1e-12, -0.5, -0.25, 0.0, 0.5, 0.5 + 1e-12)
    axes = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]],
                    dtype=float)
    origins, dirs = [], []
    for cx, cy in ((2.0, 0.0), (2.0, 2.0), (2.0, -2.0), (-2.0, 0.0), (0.0, 4.0), (-4.0, 4.0)):
        for a in offsets:
            for b in offsets:
                # along x past the shape at height b, side offset a; down/up through it
                origins += [(cx - 3.0, cy + a, b), (cx + 3.0, cy + a, b), (cx + a, cy + b, 3.0),
                            (cx + a, cy + b, -0.5), (cx + a, cy - 3.0, b)]
                dirs += [axes[0], axes[1], axes[5], axes[4], axes[2]]
    origins = np.array(origins)
    dirs = np.array(dirs)
    hits = 0
    for min_range in (0.0, 2.5, 3.0):
        for max_range in (2.5, 3.0, 10.0):
            t, _ = agree(casters, origins, dirs, max_range, min_range=min_range)
            hits += int(np.isfinite(t).sum())
    assert hits > 1000
    # the same rays from one origin each (the lidar path): all six axes from every origin,
    # and a fan through the corners and along the faces
    for c in origins[::7]:
        agree(casters, c, axes, 10.0)
        agree(casters, c, axes, 3.0, min_range=0.5)
    corners = np.array([[1.5, sy * 0.5, sz * 0.5] for sy in (-1, 1) for sz in (-1, 1)] +
                       [[1.5, 0.5, 0.0], [2.5, 0.5, 0.0], [1.5, 0.0, 0.5]])
    agree(casters, np.zeros(3), corners / np.linalg.norm(corners, axis=1)[:, None], 10.0)
    # in the floor plane and parallel to it, and leaving it from on it
    agree(casters, np.array([[0, 0, -0.5], [0, 0, -0.4], [0, 0, -0.5], [0, 0, -0.6]]),
          np.array([[1, 0, 0], [0, 1, 0], [0, 0, 1], [0, 0, 1]], dtype=float), 10.0)


def test_no_hit_empty_and_degenerate_inputs_agree():
    casters = both(grazing_scene())
    for origins, max_range, min_range in (
            (np.zeros(3), 10.0, 20.0),                      # min above max: nothing
            (np.zeros(3), float('nan'), 0.0),
            (np.zeros(3), np.inf, 0.0),
            (np.zeros(3), 10.0, -1.0),                      # negative min: from the origin
            (np.array([np.nan, 0.0, 0.0]), 10.0, 0.0),      # nowhere: nothing hit
            (np.full((8, 3), np.nan), 10.0, 0.0),
            (np.array([1e6, 0.0, 0.0]), 10.0, 0.0)):
        t, k = agree(casters, origins, fan(8), max_range, min_range=min_range)
    for caster in casters:
        t, k = caster.cast_hits(np.zeros(3), np.zeros((0, 3)), 5.0)
        assert t.shape == (0,) and k.shape == (0,)
        with pytest.raises(ValueError, match='non-zero finite'):
            caster.cast([0, 0, 0], [[0, 0, 0]], 5.0)


# ------------------------------------------------------------------------------------------
# selection and bad input

def test_the_physics_core_selects_the_ray_caster():
    for core in ('compiled', 'python'):
        pw = PhysicsWorld(Physics(), core=core)
        assert PluginContext(pw, World()).raycaster().core == core
    with pytest.raises(ValueError, match="RayCaster core must be 'compiled' or 'python'"):
        RayCaster([], core='gpu')
    with pytest.raises(ModelError, match='plane normal'):
        RayCaster([static('p', Geometry('plane', normal=(0, 0, 0)), Pose())])
    with pytest.raises(ModelError, match='no triangles'):
        RayCaster([static('m', Geometry('mesh', vertices=np.zeros((0, 3)),
                                        faces=np.zeros((0, 3), dtype=int)), Pose())])


def test_the_core_rejects_inconsistent_arrays():
    scene = _core.RayScene(2)
    eye = np.eye(3).reshape(1, 9)
    with pytest.raises(ValueError, match='shape index 5 outside'):
        scene.set_items(np.array([0], dtype=np.intc), np.array([5]), np.ones((1, 3)),
                        np.array([-1], dtype=np.intc), eye, np.zeros((1, 3)))
    with pytest.raises(ValueError, match='item rotations'):
        scene.set_items(np.array([0], dtype=np.intc), np.array([0]), np.ones((1, 3)),
                        np.array([-1], dtype=np.intc), np.eye(2), np.zeros((1, 3)))
    scene.set_items(np.array([0], dtype=np.intc), np.array([1]), np.ones((1, 3)),
                    np.array([0], dtype=np.intc), eye, np.zeros((1, 3)))
    assert scene.dynamic_slots == 1
    ray = (np.zeros(3), np.array([[1.0, 0, 0]]), True, 0.0, 5.0)
    with pytest.raises(ValueError, match='no link rows'):
        scene.cast(*ray, np.zeros((0, 4)), np.zeros((0, 3)))
    with pytest.raises(ValueError, match='slot row outside'):
        scene.set_slots(np.array([1]), eye, np.zeros((1, 3)), 1)
    scene.set_slots(np.array([0]), eye, np.array([[1.0, 0, 0]]), 1)   # 1 m ahead of its link
    with pytest.raises(ValueError, match='poses of 1 link rows'):
        scene.cast(*ray, np.zeros((0, 4)), np.zeros((0, 3)))
    link_q, link_p = np.array([[0, 0, 0, 1.0]]), np.array([[2.0, 0, 0]])
    with pytest.raises(ValueError, match='one flag per shape'):
        scene.cast(*ray, link_q, link_p, np.zeros(5, dtype=np.uint8))
    t, k = scene.cast(*ray, link_q, link_p)
    assert t.tolist() == [2.0] and k.tolist() == [1]
    t, k = scene.cast(*ray, link_q, link_p, np.array([0, 1], dtype=np.uint8))
    assert t.tolist() == [np.inf] and k.tolist() == [-1]
    # a hierarchy whose node refers to itself or outside would never end or read past it
    tri = (np.zeros((1, 3)), np.eye(3)[:1], np.eye(3)[1:2], np.array([0]))
    box = (np.zeros((2, 3)), np.ones((2, 3)))
    with pytest.raises(ValueError, match='children before it'):
        scene.set_forest(*box, np.array([0, 0]), np.array([2, 1]),
                         np.array([0, 1], dtype=np.uint8), *tri)
    with pytest.raises(ValueError, match='outside the forest'):
        scene.set_forest(*box, np.array([1, 0]), np.array([1, 2]),
                         np.array([0, 1], dtype=np.uint8), *tri)
