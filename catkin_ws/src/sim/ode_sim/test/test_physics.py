"""PhysicsWorld on hand-built descriptions: gravity, contacts, friction, joints, state changes."""
import math

import numpy as np
import pytest

from ode_sim.description.model import (Collision, Geometry, Inertial, Joint, Link, Model, ModelError,
                                       Physics, Surface, Visual)
from ode_sim.engine.physics import PhysicsWorld
from ode_sim.description.transforms import Pose


def ground():
    return Model('ground_plane', static=True, links=[Link('link', collisions=[
        Collision('c', Geometry('plane'), surface=Surface(mu1=100, mu2=50))])])


def box(name='box', z=10.0, size=(1, 1, 1), mass=1.0, mu=1.0, pose=None):
    sx, sy, sz = size
    inertial = Inertial(mass, ixx=mass * (sy ** 2 + sz ** 2) / 12,
                        iyy=mass * (sx ** 2 + sz ** 2) / 12, izz=mass * (sx ** 2 + sy ** 2) / 12)
    return Model(name, pose=pose or Pose((0, 0, z)), links=[Link(
        'link', inertial=inertial,
        collisions=[Collision('c', Geometry('box', size=size), surface=Surface(mu1=mu, mu2=mu))],
        visuals=[Visual('v', Geometry('box', size=size), color=(1, 0, 0, 1))])])


def pendulum(damping=0.0, lower=None, upper=None):
    """An arm of 1 kg, 1 m long on a revolute joint about Y at 2 m height, fixed to the world."""
    arm = Link('arm', pose=Pose((0.5, 0, 2)), inertial=Inertial(1.0, ixx=1e-3, iyy=1 / 12, izz=1 / 12),
               collisions=[Collision('c', Geometry('box', size=(1, 0.05, 0.05)))])
    j = Joint('hinge', 'revolute' if lower is not None else 'continuous', 'world', 'arm',
              anchor=np.array([0.0, 0, 2]), axis=np.array([0.0, 1, 0]), lower=lower, upper=upper,
              damping=damping)
    return Model('pendulum', links=[arm], joints=[j])


def test_dropped_box_follows_g_within_one_percent():
    pw = PhysicsWorld(Physics())
    m = pw.add_model(box(z=20.0))
    pw.step(1000)
    fall = 20.0 - m.pose().p[2]
    assert fall == pytest.approx(0.5 * 9.8 * 1.0 ** 2, rel=0.01)
    assert pw.time == pytest.approx(1.0)


def test_box_rests_on_ground_and_does_not_drift():
    pw = PhysicsWorld(Physics())
    pw.add_model(ground())
    m = pw.add_model(box(z=0.5))
    pw.step(500)
    p0 = m.pose().p.copy()
    pw.step(60000)          # one simulated minute
    assert m.pose().p[2] == pytest.approx(0.5, abs=0.002)
    assert np.linalg.norm(m.pose().p[:2] - p0[:2]) < 0.001


def test_friction_holds_a_pushed_box_until_the_force_exceeds_mu_m_g():
    pw = PhysicsWorld(Physics())
    pw.add_model(ground())
    m = pw.add_model(box(z=0.5, mu=0.5))
    pw.step(200)
    link = m.links['link']
    for _ in range(500):            # 0.4 * m g < mu m g: stays
        link.add_force((0.4 * 9.8, 0, 0))
        pw.step()
    assert abs(m.pose().p[0]) < 0.002
    for _ in range(500):            # 0.8 * m g > mu m g: slides with a = 0.3 g
        link.add_force((0.8 * 9.8, 0, 0))
        pw.step()
    assert m.twist()[0][0] == pytest.approx(0.3 * 9.8 * 0.5, rel=0.1)


def test_pendulum_swings_and_limits_stop_it():
    pw = PhysicsWorld(Physics())
    m = pw.add_model(pendulum())
    j = m.joints['hinge']
    assert j.position() == pytest.approx(0.0)
    pw.step(300)
    assert j.position() > 0.3       # +Y rotation takes +X towards -Z: gravity pulls it down
    pw2 = PhysicsWorld(Physics())
    m2 = pw2.add_model(pendulum(lower=-0.2, upper=0.2))
    pw2.step(2000)
    assert m2.joints['hinge'].position() == pytest.approx(0.2, abs=0.02)


def test_velocity_motor_and_effort():
    pw = PhysicsWorld(Physics(), gravity=(0, 0, 0))
    m = pw.add_model(pendulum())
    j = m.joints['hinge']
    j.set_velocity(2.0, fmax=100)
    pw.step(100)
    assert j.velocity() == pytest.approx(2.0, rel=1e-3)
    j.release()
    pw.step(10)
    inertia = 1 / 12 + 1 * 0.5 ** 2         # about the hinge
    v0 = j.velocity()
    j.set_effort(1.0)
    pw.step(1000)
    assert j.velocity() - v0 == pytest.approx(1.0 / inertia * 1.0, rel=0.02)


def test_position_target_and_configuration():
    pw = PhysicsWorld(Physics())
    m = pw.add_model(pendulum())
    j = m.joints['hinge']
    j.set_position_target(-0.5)
    pw.step(1000)
    assert j.position() == pytest.approx(-0.5, abs=1e-3)
    j.release()
    m.set_configuration({'hinge': 1.0})
    assert j.position() == pytest.approx(1.0, abs=1e-6)
    tip = m.links['arm'].pose().apply([0.5, 0, 0])
    assert tip == pytest.approx([math.cos(1.0), 0, 2 - math.sin(1.0)], abs=1e-6)
    with pytest.raises(ModelError, match="no joint 'nope'"):
        m.set_configuration({'nope': 1})


def test_set_pose_twist_reset_and_remove():
    pw = PhysicsWorld(Physics(), gravity=(0, 0, 0))
    m = pw.add_model(box(z=1.0))
    m.set_pose(Pose.from_xyz_rpy((2, 3, 4), (0, 0, 1.0)))
    assert m.pose().p == pytest.approx([2, 3, 4])
    assert m.pose().rpy()[2] == pytest.approx(1.0)
    m.set_twist((1, 0, 0), (0, 0, 0))
    pw.step(1000)
    assert m.pose().p == pytest.approx([3, 3, 4], abs=1e-6)
    pw.reset_world()
    assert m.pose().p == pytest.approx([0, 0, 1])
    assert pw.time == pytest.approx(1.0)
    pw.reset_time()
    assert pw.time == 0.0
    v = pw.version
    assert pw.remove_model('box')
    assert not pw.remove_model('box')
    assert pw.version > v and 'box' not in pw.models
    pw.step(10)


def test_shapes_follow_links_and_static_models():
    pw = PhysicsWorld(Physics())
    pw.add_model(ground())
    pw.add_model(box(z=3.0))
    shapes = {s.key: s for s in pw.collision_shapes()}
    assert shapes['ground_plane::link::c'].static
    b = shapes['box::link::c']
    z0 = b.world_pose().p[2]
    pw.step(100)
    assert b.world_pose().p[2] < z0
    vis = pw.visual_shapes()
    assert [s.color for s in vis] == [(1, 0, 0, 1)]


def test_bad_models_are_refused_with_their_name():
    pw = PhysicsWorld(Physics())
    pw.add_model(box())
    with pytest.raises(ModelError, match="already exists"):
        pw.add_model(box())
    zero = box('zero', mass=0.0)
    with pytest.raises(ModelError, match="link 'link' of model 'zero' has no positive mass"):
        pw.add_model(zero)
    bad = pendulum()
    bad.joints[0].child = 'ghost'
    with pytest.raises(ModelError, match="unknown links"):
        pw.add_model(bad)


def test_mesh_collision_becomes_its_bounding_box_with_a_warning_on_the_python_core():
    """core='python' (PyODE has no trimesh); the compiled core: test_trimesh.py"""
    verts = np.array([[0, 0, 0], [1, 0, 0], [0, 2, 0], [0, 0, 3]], dtype=float) + [1, 1, 0]
    faces = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    mesh = Geometry('mesh', uri='model://thing/meshes/t.stl', vertices=verts, faces=faces)
    m = box('thing', z=5.0)
    m.links[0].collisions = [Collision('c', mesh)]
    pw = PhysicsWorld(Physics(), core='python')
    pw.add_model(ground())
    pw.add_model(m)
    shape = [s for s in pw.collision_shapes() if s.model == 'thing'][0]
    assert shape.geometry.kind == 'box' and shape.geometry.size == pytest.approx((1, 2, 3))
    assert shape.world_pose().p == pytest.approx([1.5, 2.0, 6.5])
    assert any("mesh 'model://thing/meshes/t.stl' simulated as its bounding box" in w
               for w in m.warnings)
    pw.step(3000)
    corners = np.array([[x, y, z] for x in (-.5, .5) for y in (-1, 1) for z in (-1.5, 1.5)])
    lowest = shape.world_pose().apply(corners)[:, 2].min()
    assert lowest == pytest.approx(0.0, abs=0.01)   # the box lies on the ground, not in it


def test_link_welded_to_the_world_is_static_even_inside_the_ground():
    """A base fixed to 'world' (URDF world link) whose box reaches into the ground plane: no
    body, no contact fight; the arm on it still swings on its hinge."""
    base = Link('base', inertial=Inertial(5.0, ixx=.1, iyy=.1, izz=.1),
                collisions=[Collision('c', Geometry('box', size=(0.2, 0.2, 0.2)))])
    arm = pendulum().links[0]
    hinge = Joint('hinge', 'continuous', 'base', 'arm', anchor=np.array([0.0, 0, 2]),
                  axis=np.array([0.0, 1, 0]))
    weld = Joint('fix', 'fixed', 'world', 'base')
    pw = PhysicsWorld(Physics())
    pw.add_model(ground())
    m = pw.add_model(Model('robot', links=[base, arm], joints=[weld, hinge]))
    assert m.links['base'].body is None and 'fix' not in m.joints
    angles = []
    for _ in range(2000):
        pw.step()
        angles.append(m.joints['hinge'].position())
    assert m.links['base'].pose().p == pytest.approx([0, 0, 0])
    # an undamped swing from horizontal: down through pi/2 to the other horizontal and back
    assert max(angles) == pytest.approx(math.pi, abs=0.05) and min(angles) > -0.05


def test_time_accumulates_across_a_change_of_step():
    """SetPhysicsProperties changing max_step_size must not make the clock jump or go back."""
    pw = PhysicsWorld(Physics())
    pw.step(1000)                          # 1 s of 1 ms steps
    assert pw.time == pytest.approx(1.0)
    pw.set_properties(time_step=0.004)
    assert pw.time == pytest.approx(1.0)   # no jump at the change
    pw.step(250)                           # + 1 s of 4 ms steps
    assert pw.time == pytest.approx(2.0)
    pw.set_properties(time_step=0.0005)
    before = pw.time
    pw.step(1)
    assert pw.time == pytest.approx(before + 0.0005)   # never backwards
    pw.step(1999)
    assert pw.time == pytest.approx(3.0)
    pw.reset_time()
    pw.step(2)
    assert pw.time == pytest.approx(0.001)


def test_set_properties_rejects_a_non_positive_step_and_sets_gravity():
    pw = PhysicsWorld(Physics())
    with pytest.raises(ValueError, match='time_step must be positive'):
        pw.set_properties(time_step=0.0)
    pw.set_properties(gravity=(0.0, 0.0, -1.0))
    assert pw.gravity == pytest.approx((0.0, 0.0, -1.0))
    m = pw.add_model(box(z=20.0))
    pw.step(1000)
    assert 20.0 - m.pose().p[2] == pytest.approx(0.5, rel=0.01)


@pytest.mark.parametrize('core', ['compiled', 'python'])
def test_a_static_model_moves_with_its_geoms(core):
    """set_pose on a static model (Gazebo's SetWorldPose; the window's move tool) re-places its
    geoms: a ray finds the moved table, a box dropped there lands on it."""
    from ode_sim.engine.raycast import RayCaster
    pw = PhysicsWorld(Physics(), core=core)
    pw.add_model(ground())
    table = box('table', pose=Pose((5, 0, 0.25)), size=(2, 2, 0.5))
    table.static = True
    t = pw.add_model(table)
    b = pw.add_model(box('b', z=1.0, size=(0.2, 0.2, 0.2)))
    b.set_pose(Pose((0, 0, 0.1)))
    pw.step(2000)                               # settles, and may fall asleep
    version = pw.version
    t.set_pose(Pose((0, 0, 0.15)))              # under the box: it must be pushed up / rest on it
    assert pw.version != version
    assert np.allclose(t.pose().p, (0, 0, 0.15))
    assert np.allclose(t.links['link'].pose().p, (0, 0, 0.15))
    rc = RayCaster(pw.collision_shapes(), core=core)
    d = rc.cast(np.array([[0.0, -3.0, 0.2]]), np.array([[0.0, 1.0, 0.0]]), 10.0)
    assert float(np.ravel(d[0] if isinstance(d, tuple) else d)[0]) == pytest.approx(2.0, abs=1e-6)
    b.set_pose(Pose((0, 0, 0.8)))
    pw.step(2000)
    assert b.pose().p[2] == pytest.approx(0.4 + 0.1, abs=0.01)  # on the table's top at 0.4
