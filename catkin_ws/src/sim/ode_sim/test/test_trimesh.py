"""Mesh collisions in the compiled core: libode trimesh geoms on the loaded triangles (not their
bounding boxes), for world objects and robot links; the ray caster sees the same arrays.
core='python' keeps the bounding box with its warning (test_physics.py)."""
import math
import os

import numpy as np
import pytest

from ode_sim.description.model import (Collision, Geometry, Inertial, Link, Model, Physics,
                                       Surface)
from ode_sim.description.transforms import Pose
from ode_sim.description import sdf
from ode_sim.description.urdf import parse_urdf
from ode_sim.engine import _core
from ode_sim.engine.physics import PhysicsWorld
from ode_sim.engine.raycast import RayCaster


HERE = os.path.dirname(os.path.abspath(__file__))
CUBE = os.path.join(HERE, 'fixtures', 'loaders', 'meshes', 'cube_ascii.stl')


def ground():
    return Model('ground_plane', static=True, links=[Link('link', collisions=[
        Collision('c', Geometry('plane'), surface=Surface(mu1=100, mu2=50))])])


def box(z=10.0, size=(1, 1, 1), mass=1.0, mu=1.0, pose=None):
    sx, sy, sz = size
    inertial = Inertial(mass, ixx=mass * (sy ** 2 + sz ** 2) / 12,
                        iyy=mass * (sx ** 2 + sz ** 2) / 12, izz=mass * (sx ** 2 + sy ** 2) / 12)
    return Model('box', pose=pose or Pose((0, 0, z)), links=[Link(
        'link', inertial=inertial,
        collisions=[Collision('c', Geometry('box', size=size), surface=Surface(mu1=mu, mu2=mu))])])


def trough():
    """A static open surface, normals up: a flat bottom at z=0 for |x| < 1, walls up to z=1 at
    |x| = 1.5, 4 m long in y. Its bounding box top is z=1; a box in it rests on z=0."""
    xs = [-1.5, -1.0, 1.0, 1.5]
    zs = [1.0, 0.0, 0.0, 1.0]
    v = [(x, y, z) for x, z in zip(xs, zs) for y in (-2.0, 2.0)]
    f = []
    for i in range(3):
        a, b, c, d = 2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 3      # (x_i,-y) (x_i,+y) (x_i+1,..)
        f += [(a, c, b), (b, c, d)]
    return np.array(v, dtype=float), np.array(f, dtype=np.int64)


def ramp(angle):
    """A static wedge's slope as an open surface rising along +x at `angle`, 4 x 4 m."""
    h = 4.0 * math.tan(angle)
    v = np.array([(-2, -2, 0), (2, -2, h), (-2, 2, 0), (2, 2, h)], dtype=float)
    return v, np.array([(0, 1, 2), (2, 1, 3)], dtype=np.int64)


def static_mesh(name, v, f, mu=1.0):
    g = Geometry('mesh', uri='model://%s/meshes/m.stl' % name, vertices=v, faces=f)
    return Model(name, static=True, links=[Link('link', collisions=[
        Collision('c', g, surface=Surface(mu1=mu, mu2=mu))])])


def prism_wheel(radius=0.1, width=0.05, n=48):
    """A closed n-gon prism about the y axis (a mesh wheel), outward normals."""
    a = np.arange(n) * 2 * math.pi / n
    ring = np.stack([radius * np.cos(a), np.zeros(n), radius * np.sin(a)], axis=1)
    v = np.concatenate([ring + [0, -width / 2, 0], ring + [0, width / 2, 0],
                        [[0, -width / 2, 0], [0, width / 2, 0]]])
    f = []
    for i in range(n):
        j = (i + 1) % n
        f += [(i, j, n + i), (j, n + j, n + i)]           # side
        f += [(2 * n, j, i), (2 * n + 1, n + i, n + j)]   # caps
    f = np.array(f, dtype=np.int64)
    # orient every face outward (its normal away from the axis / centre)
    tri = v[f]
    nrm = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    out = tri.mean(axis=1)
    flip = np.einsum('ij,ij->i', nrm, out) < 0
    f[flip] = f[flip][:, [0, 2, 1]]
    return v, f


def test_box_rests_on_the_triangles_of_a_concave_mesh_not_its_bounding_box():
    v, f = trough()
    m = static_mesh('trough', v, f)
    pw = PhysicsWorld(Physics())
    pw.add_model(m)
    b = pw.add_model(box(z=1.5, size=(0.4, 0.4, 0.4)))
    assert not m.warnings
    pw.step(2000)
    p = b.pose().p
    assert p[2] == pytest.approx(0.2, abs=0.005), 'bounding box would give 1.2'
    assert abs(p[0]) < 0.01 and abs(p[1]) < 0.01
    assert pw._contacts > 0


def test_box_rests_on_a_sloped_mesh_with_friction():
    angle = math.radians(15)
    v, f = ramp(angle)
    pw = PhysicsWorld(Physics())
    pw.add_model(static_mesh('ramp', v, f, mu=1.0))
    # placed just above the slope at x=0 (surface height 2 tan15 = 0.536), tilted with it
    z0 = 2 * math.tan(angle)
    q = (0.0, -math.sin(angle / 2), 0.0, math.cos(angle / 2))     # x y z w: pitch up along +x
    half = 0.1 / math.cos(angle)
    b = pw.add_model(box(size=(0.2, 0.2, 0.2), mu=1.0, pose=Pose((0, 0, z0 + half + 0.01), q)))
    pw.step(1500)
    p = b.pose().p
    surface = (p[0] + 2) * math.tan(angle)
    assert p[2] - surface == pytest.approx(half, abs=0.005), 'rests on the slope'
    assert abs(p[0]) < 0.02                    # mu 1 > tan 15°: it does not slide
    # the bounding box of the ramp (top at z = 4 tan15 = 1.07) would hold it at 1.17


def test_mesh_wheel_collides_and_rolls():
    """A free mesh wheel (48-gon prism) on the ground plane rolls without slipping: it rests
    at its radius and travels omega * r; its bounding box would tumble, not roll."""
    r = 0.1
    v, f = prism_wheel(r)
    mass = 1.0
    inertial = Inertial(mass, ixx=mass * r * r / 4, iyy=mass * r * r / 2, izz=mass * r * r / 4)
    wheel = Model('wheel', pose=Pose((0, 0, r + 0.02)), links=[Link(
        'link', inertial=inertial, collisions=[Collision(
            'c', Geometry('mesh', uri='wheel.stl', vertices=v, faces=f),
            surface=Surface(mu1=1.0, mu2=1.0))])])
    pw = PhysicsWorld(Physics())
    pw.add_model(ground())
    w = pw.add_model(wheel)
    assert not wheel.warnings
    pw.step(300)
    assert w.pose().p[2] == pytest.approx(r * math.cos(math.pi / 48), abs=0.003)
    w.wake()
    w.canonical.body.setAngularVel((0, 5.0, 0))           # about +y: rolls towards +x
    w.canonical.body.setLinearVel((5.0 * r, 0, 0))        # omega r: rolling, no slip
    x0 = w.pose().p[0]
    pw.step(1000)
    assert 0.4 < w.pose().p[0] - x0 < 0.51     # 0.5 m less the facets' bumps; a box stops in 1 cm
    assert w.pose().p[2] == pytest.approx(r, abs=0.01)


def test_urdf_robot_with_an_stl_mesh_body_collides_without_the_warning():
    urdf = """<robot name="r"><link name="base">
      <inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
      <collision><geometry><mesh filename="file://%s" scale="0.5 0.5 0.5"/></geometry></collision>
    </link></robot>""" % CUBE
    m = parse_urdf(urdf, 'test.urdf', 'r')
    g = m.links[0].collisions[0].geometry
    assert g.kind == 'mesh'
    lo, hi = g.vertices.min(axis=0), g.vertices.max(axis=0)
    m.pose = Pose((0, 0, 1.0))
    pw = PhysicsWorld(Physics())
    pw.add_model(ground())
    sm = pw.add_model(m)
    assert not [w for w in m.warnings if 'bounding box' in w]
    pw.step(1500)
    lowest = (sm.canonical.pose() * Pose()).apply(g.vertices)[:, 2].min()
    assert lowest == pytest.approx(0.0, abs=0.005)
    assert (hi - lo).max() > 0


def test_ray_caster_and_collision_share_the_loaded_triangles():
    v, f = trough()
    pw = PhysicsWorld(Physics())
    pw.add_model(static_mesh('trough', v, f))
    shape = [s for s in pw.collision_shapes() if s.model == 'trough'][0]
    assert shape.geometry.kind == 'mesh'
    assert shape.geometry.vertices is v and shape.geometry.faces is f
    geom = pw.models['trough'].links['link'].geoms[0]
    assert _core.is_trimesh(geom._id()) and geom.data.triangles == len(f)
    # one ODE copy per loaded mesh: a second model of the same arrays shares it
    geom2 = pw.add_model(static_mesh('trough2', v, f)).links['link'].geoms[0]
    assert geom2.data is geom.data
    # the lidar hits the bottom (z=0) inside the trough, where the box would rest
    rc = RayCaster(pw.collision_shapes())
    t, who = rc.cast_hits([0, 0, 0.5], np.array([[0, 0, -1.0], [1.0, 0, -1.0]]), 5.0)
    assert t[0] == pytest.approx(0.5)
    assert t[1] == pytest.approx(math.sqrt(2) * 0.5)


def test_removing_a_mesh_model_destroys_its_geoms():
    v, f = prism_wheel()
    m = static_mesh('w', v, f)
    pw = PhysicsWorld(Physics())
    sm = pw.add_model(m)
    geom = sm.links['link'].geoms[0]
    assert geom.getSpace() is not None
    assert pw.remove_model('w')
    assert geom.getSpace() is None and geom.id == 0
    pw.add_model(ground())
    b = pw.add_model(box(z=0.5))
    pw.step(200)
    assert b.pose().p[2] == pytest.approx(0.5, abs=0.005)


def test_python_core_keeps_the_bounding_box_warning():
    v, f = trough()
    m = static_mesh('trough', v, f)
    pw = PhysicsWorld(Physics(), core='python')
    pw.add_model(m)
    assert any('simulated as its bounding box' in w for w in m.warnings)


def test_sdf_world_with_a_scaled_obj_mesh_floor():
    """An SDF world whose floor is an OBJ quad scaled 4 x 4 and raised 0.3 m: the box rests on
    its triangles (the OBJ loader and <scale> of the description layer)."""
    obj = os.path.join(HERE, 'fixtures', 'loaders', 'meshes', 'square.obj')
    world = sdf.parse_world("""<sdf version="1.6"><world name="w">
      <model name="floor"><static>true</static><pose>-2 -2 0.3 0 0 0</pose><link name="l">
        <collision name="c"><geometry><mesh><uri>file://%s</uri><scale>4 4 1</scale></mesh>
        </geometry></collision></link></model></world></sdf>""" % obj, 'w.world')
    pw = PhysicsWorld(world.physics, world.gravity)
    for m in world.models:
        pw.add_model(m)
    assert not any('bounding box' in w for m in world.models for w in m.warnings)
    b = pw.add_model(box(z=1.0, size=(0.2, 0.2, 0.2)))
    pw.step(1500)
    assert b.pose().p[2] == pytest.approx(0.4, abs=0.005)
