"""Ray caster: analytic distances per geometry kind, exclusion, dynamic shapes, and agreement
with ODE's own ray geom (pyODE) on the same shapes; every test on both cores (the compiled
ray casting and the NumPy reference; test_raycast_core.py compares them directly)."""
import math

import numpy as np
import pytest

from ode_sim.description import meshgen
from ode_sim.description.model import Geometry, ModelError
from ode_sim.engine import raycast
from ode_sim.engine.raycast import scan_directions
from ode_sim.engine.scene import ShapeInstance
from ode_sim.description.transforms import Pose


def shape(key, geometry, pose=None, link_pose=None, model=None, link='link', local=None):
    return ShapeInstance(key=key, model=model or key, link=link, geometry=geometry,
                         local=local or Pose(), static_pose=pose or Pose(),
                         link_pose=link_pose)


def box(key, size, xyz, rpy=(0, 0, 0), **kw):
    return shape(key, Geometry('box', size=tuple(size)), Pose.from_xyz_rpy(xyz, rpy), **kw)


def uv_sphere(radius, n_lat=12, n_lon=24):
    """A closed triangulated sphere (vertices, faces): the model library's ellipsoid."""
    part = meshgen.ellipsoid((radius, radius, radius), segments=n_lon, rings=n_lat)
    return part.vertices, part.faces


def box_mesh(size):
    hx, hy, hz = np.asarray(size) / 2.0
    v = np.array([[sx * hx, sy * hy, sz * hz] for sx in (-1, 1) for sy in (-1, 1)
                  for sz in (-1, 1)])
    f = np.array([[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                  [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]])
    return v, f


CORE = {}


@pytest.fixture(autouse=True, params=['compiled', 'python'])
def core(request):
    CORE['now'] = request.param
    yield request.param
    CORE.clear()


def make(shapes):
    """A RayCaster on the core of the running test."""
    return raycast.RayCaster(shapes, core=CORE['now'])


RING = np.array([[1, 0, 0], [0, 1, 0], [-1, 0, 0], [0, -1, 0]], dtype=float)


def test_walls_in_four_directions():
    shapes = [box('east', (0.2, 10, 2), (3.1, 0, 0)), box('north', (10, 0.2, 2), (0, 2.1, 0)),
              box('west', (0.2, 10, 2), (-4.1, 0, 0)), box('south', (10, 0.2, 2), (0, -1.6, 0))]
    d = make(shapes).cast(np.zeros(3), RING, 10.0)
    np.testing.assert_allclose(d, [3.0, 2.0, 4.0, 1.5], atol=1e-9)


def test_nothing_within_range_is_inf_and_max_range_is_respected():
    rc = make([box('east', (0.2, 10, 2), (3.1, 0, 0))])
    d = rc.cast(np.zeros(3), RING, 10.0)
    assert d[0] == pytest.approx(3.0) and np.all(np.isinf(d[1:]))
    assert np.isinf(rc.cast(np.zeros(3), RING, 2.9)[0])
    assert make([]).cast([0, 0, 0], RING, 5.0).tolist() == [np.inf] * 4


def test_sphere_and_cylinder_analytic():
    shapes = [shape('ball', Geometry('sphere', radius=0.5), Pose((2, 0, 0))),
              shape('can', Geometry('cylinder', radius=0.3, length=1.0), Pose((0, 3, 0))),
              shape('lying', Geometry('cylinder', radius=0.25, length=2.0),
                    Pose.from_xyz_rpy((-2, 0, 0), (math.pi / 2, 0, 0)))]
    rc = make(shapes)
    d = rc.cast(np.zeros(3), RING, 10.0)
    assert d[0] == pytest.approx(1.5, abs=1e-12)
    assert d[1] == pytest.approx(2.7, abs=1e-12)
    assert d[2] == pytest.approx(1.75, abs=1e-12)
    # off-centre ray on the sphere: chord geometry
    y = 0.3
    d = rc.cast([0, y, 0], [[1, 0, 0]], 10.0)
    assert d[0] == pytest.approx(2 - math.sqrt(0.25 - y * y), abs=1e-12)
    # the upright cylinder's flat cap from above, and just beside it
    d = rc.cast([[0, 3.2, 5], [0, 3.31, 5]], [[0, 0, -1], [0, 0, -1]], 10.0)
    assert d[0] == pytest.approx(4.5, abs=1e-12) and np.isinf(d[1])


def test_mesh_hits_analytic_and_inside_reports_exit():
    v, f = box_mesh((1, 2, 3))
    rc = make([shape('crate', Geometry('mesh', vertices=v, faces=f), Pose((4, 0, 0)))])
    d = rc.cast(np.zeros(3), RING, 10.0)
    assert d[0] == pytest.approx(3.5, abs=1e-12) and np.all(np.isinf(d[1:]))
    d = rc.cast([4, 0, 0], RING, 10.0)        # from inside: the nearest face ahead
    np.testing.assert_allclose(d, [0.5, 1.0, 0.5, 1.0], atol=1e-12)
    v, f = uv_sphere(1.0, 16, 32)
    rc = make([shape('ball', Geometry('mesh', vertices=v, faces=f), Pose((0, 0, 5)))])
    d = rc.cast(np.zeros(3), [[0, 0, 1]], 10.0)
    assert d[0] == pytest.approx(4.0, abs=1e-12)   # a vertex sits on the pole


def test_solids_from_inside_report_the_exit_point():
    shapes = [box('b', (2, 2, 2), (0, 0, 0)), ]
    np.testing.assert_allclose(make(shapes).cast(np.zeros(3), RING, 5), [1, 1, 1, 1])
    s = [shape('s', Geometry('sphere', radius=2.0), Pose((0.5, 0, 0)))]
    np.testing.assert_allclose(make(s).cast(np.zeros(3), RING[:1], 5), [2.5])
    c = [shape('c', Geometry('cylinder', radius=1.0, length=4.0), Pose())]
    np.testing.assert_allclose(make(c).cast(np.zeros(3), [[1, 0, 0], [0, 0, 1]], 5),
                               [1.0, 2.0])


def test_plane_is_two_sided_for_rays():
    rc = make([shape('ground', Geometry('plane', normal=(0, 0, 1)), Pose((0, 0, -1)))])
    d = rc.cast([[0, 0, 0], [0, 0, -2], [0, 0, -2], [0, 0, 0]],
                [[0, 0, -1], [0, 0, 1], [0, 0, -1], [1, 0, 0]], 10.0)
    assert d[0] == pytest.approx(1.0) and d[1] == pytest.approx(1.0)
    assert np.isinf(d[2]) and np.isinf(d[3])
    s = math.sqrt(0.5)
    assert rc.cast([0, 0, 0], [[s, 0, -s]], 10.0)[0] == pytest.approx(math.sqrt(2))


def test_rotated_box():
    # a 2 x 0.2 wall at x = 2 turned 45 degrees about Z: the ray along X meets its face
    # where x - 2 = -(0.1 / cos 45)
    rc = make([box('w', (0.2, 2, 1), (2, 0, 0), (0, 0, math.pi / 4))])
    d = rc.cast(np.zeros(3), RING[:1], 10.0)
    assert d[0] == pytest.approx(2 - 0.1 * math.sqrt(2), abs=1e-12)
    # box rolled 90 degrees about X: its 3 m long Z side now lies along Y
    rc = make([box('w', (0.5, 0.5, 3.0), (0, 4, 0), (math.pi / 2, 0, 0))])
    assert rc.cast(np.zeros(3), RING[1:2], 10.0)[0] == pytest.approx(2.5, abs=1e-12)


def test_exclusion_by_pairs_and_callable():
    shapes = [box('own', (0.3, 0.3, 0.3), (0, 0, 0), model='robot', link='base_scan'),
              box('far', (0.2, 10, 2), (3.1, 0, 0))]
    rc = make(shapes)
    assert rc.cast(np.zeros(3), RING[:1], 10.0)[0] == pytest.approx(0.15)
    assert rc.cast(np.zeros(3), RING[:1], 10.0,
                   exclude={('robot', 'base_scan')})[0] == pytest.approx(3.0)
    assert rc.cast(np.zeros(3), RING[:1], 10.0,
                   exclude=lambda s: s.link == 'base_scan')[0] == pytest.approx(3.0)
    # meshes too, static and dynamic
    v, f = box_mesh((0.3, 0.3, 0.3))
    m = [shape('own', Geometry('mesh', vertices=v, faces=f), Pose(), model='robot',
               link='base_scan'),
         shape('own2', Geometry('mesh', vertices=v, faces=f), link_pose=lambda: Pose(),
               model='robot', link='base_scan'), shapes[1]]
    rc = make(m)
    assert rc.cast(np.zeros(3), RING[:1], 10.0)[0] == pytest.approx(0.15)
    assert rc.cast(np.zeros(3), RING[:1], 10.0,
                   exclude={('robot', 'base_scan')})[0] == pytest.approx(3.0)


def test_dynamic_shapes_are_reposed_on_every_cast():
    where = {'p': Pose((3, 0, 0))}
    v, f = box_mesh((0.2, 0.2, 0.2))
    shapes = [shape('cart', Geometry('box', size=(0.2, 0.2, 0.2)), link_pose=lambda: where['p']),
              shape('ball', Geometry('sphere', radius=0.1), link_pose=lambda: where['p'],
                    local=Pose((0, 2, 0))),
              shape('crate', Geometry('mesh', vertices=v, faces=f), link_pose=lambda: where['p'],
                    local=Pose((0, -2, 0))),
              shape('can', Geometry('cylinder', radius=0.1, length=1),
                    link_pose=lambda: where['p'], local=Pose((-6, 0, 0)))]
    rc = make(shapes)
    o = np.zeros(3)
    dirs = np.array([[1, 0, 0], [3, 2, 0], [3, -2, 0], [-1, 0, 0]], float)
    dirs /= np.linalg.norm(dirs, axis=1)[:, None]
    d1 = rc.cast(o, dirs, 20.0)
    assert d1[0] == pytest.approx(2.9) and d1[3] == pytest.approx(2.9)
    assert np.all(np.isfinite(d1))
    where['p'] = Pose((5, 0, 0))
    d2 = rc.cast(o, dirs, 20.0)
    assert d2[0] == pytest.approx(4.9) and d2[3] == pytest.approx(0.9)
    assert np.isinf(d2[1]) and np.isinf(d2[2])   # moved off those rays


def test_rays_per_origin_and_bad_input():
    rc = make([box('east', (0.2, 10, 2), (3.1, 0, 0))])
    d = rc.cast([[0, 0, 0], [1, 0, 0], [2.5, 1, 0]], [[1, 0, 0]] * 3, 10.0)
    np.testing.assert_allclose(d, [3.0, 2.0, 0.5])
    with pytest.raises(ValueError):
        rc.cast(np.zeros((2, 3)), np.zeros((3, 3)), 1.0)
    with pytest.raises(ValueError, match='non-zero'):
        rc.cast(np.zeros(3), [[0, 0, 0]], 1.0)
    # directions that are not unit vectors still give distances
    np.testing.assert_allclose(rc.cast(np.zeros(3), [[2, 0, 0], [0.5, 0, 0]], 10.0), [3, 3])
    with pytest.raises(ModelError, match='torus'):
        make([shape('x', Geometry('torus'))])
    with pytest.raises(ModelError, match='no triangles'):
        make([shape('x', Geometry('mesh', uri='model://x/a.dae'))])


def test_scan_directions_order_matches_gazebo():
    d = scan_directions({'samples': 3, 'min_angle': -math.pi / 2, 'max_angle': math.pi / 2,
                         'v_samples': 2, 'v_min_angle': 0.0, 'v_max_angle': math.pi / 4,
                         'range_min': 0.1, 'range_max': 5})
    assert d.shape == (6, 3)
    np.testing.assert_allclose(d[:3], [[0, -1, 0], [1, 0, 0], [0, 1, 0]], atol=1e-12)
    s = math.sqrt(0.5)
    np.testing.assert_allclose(d[3:], [[0, -s, s], [s, 0, s], [0, s, s]], atol=1e-12)
    one = scan_directions({'samples': 1, 'min_angle': 1.0, 'max_angle': 2.0, 'range_max': 1})
    np.testing.assert_allclose(one, [[1, 0, 0]])


# ---------------------------------------------------------------------------------------------
# the same geometry in ODE

def _ode_distance(ode, geoms, origin, direction, max_range):
    ray = ode.GeomRay(None, max_range)
    ray.set(tuple(origin), tuple(direction))
    best = np.inf
    for g in geoms:
        for c in ode.collide(ray, g):
            best = min(best, c.getContactGeomParams()[2])
    return best


def _ode_geom(ode, s):
    g = s.geometry
    pose = s.world_pose()
    if g.kind == 'box':
        geom = ode.GeomBox(None, tuple(g.size))
    elif g.kind == 'sphere':
        geom = ode.GeomSphere(None, g.radius)
    elif g.kind == 'cylinder':
        geom = ode.GeomCylinder(None, g.radius, g.length)
    elif g.kind == 'plane':
        n = pose.rotate(g.normal)
        return ode.GeomPlane(None, tuple(n), float(np.dot(n, pose.p)))
    else:   # Debian's pyODE has no trimesh: our box-shaped meshes meet ODE as the box
        geom = ode.GeomBox(None, tuple(g.vertices.max(axis=0) - g.vertices.min(axis=0)))
    geom.setPosition(tuple(pose.p))
    geom.setRotation(tuple(pose.rotation().reshape(-1)))
    return geom


def _ode_scene():
    v_ball, f_ball = box_mesh((1.2, 0.6, 0.9))
    v_crate, f_crate = box_mesh((0.8, 0.5, 0.4))
    shapes = [box('b1', (1.0, 0.4, 0.7), (2.0, 0.5, 0.1), (0.3, 0.2, 0.9)),
              box('b2', (0.3, 2.0, 1.0), (-2.0, -1.0, 0.0), (0, 0, -0.4)),
              shape('s1', Geometry('sphere', radius=0.45), Pose((0.5, 2.5, 0.3))),
              shape('c1', Geometry('cylinder', radius=0.35, length=1.2),
                    Pose.from_xyz_rpy((-1.0, 2.0, 0.0), (0.5, 0.1, 0))),
              shape('c2', Geometry('cylinder', radius=0.2, length=0.6),
                    Pose.from_xyz_rpy((1.5, -2.0, 0.2), (0, 0, 0))),
              shape('m1', Geometry('mesh', vertices=v_ball, faces=f_ball),
                    Pose.from_xyz_rpy((-2.5, 1.5, 0.2), (0.1, 0.2, 0.3))),
              shape('m2', Geometry('mesh', vertices=v_crate, faces=f_crate),
                    link_pose=lambda: Pose.from_xyz_rpy((0.0, -2.5, 0.0), (0, 0.3, 1.0))),
              shape('ground', Geometry('plane', normal=(0, 0, 1)), Pose((0, 0, -0.6)))]
    return shapes


def _check_against_ode(ode, rc, shapes, origins, dirs, max_range, min_range=0.0):
    """Our distances vs ODE rays that start at min_range (as Gazebo's do)."""
    geoms = [_ode_geom(ode, s) for s in shapes]
    ours = rc.cast(origins, dirs, max_range, min_range=min_range)
    starts = np.broadcast_to(origins, dirs.shape) + min_range * dirs
    theirs = min_range + np.array([_ode_distance(ode, geoms, o, d, max_range - min_range)
                                   for o, d in zip(starts, dirs)])
    hit = np.isfinite(theirs)
    np.testing.assert_array_equal(np.isfinite(ours), hit)
    np.testing.assert_allclose(ours[hit], theirs[hit], atol=1e-6, rtol=0)
    return hit


def test_agrees_with_ode_ray_geom():
    """Rays with their own origins (the BVH walk and the dense tests)."""
    import ode   # Debian's python3-pyode: missing = broken install
    rng = np.random.default_rng(7)
    shapes = _ode_scene()
    rc = make(shapes)
    n = 80
    origins = rng.uniform(-0.4, 0.4, (n, 3))
    dirs = rng.normal(size=(n, 3))
    dirs[:, 2] *= 0.5                       # mostly sideways, like a lidar, some to the floor
    dirs /= np.linalg.norm(dirs, axis=1)[:, None]
    hit = _check_against_ode(ode, rc, shapes, origins, dirs, 6.0)
    assert hit.sum() >= 40                  # the test exercises real hits
    kinds = {shapes[k].geometry.kind for k in rc.cast_hits(origins, dirs, 6.0)[1] if k >= 0}
    assert kinds == {'box', 'sphere', 'cylinder', 'mesh', 'plane'}
    hit = _check_against_ode(ode, rc, shapes, origins, dirs, 6.0, min_range=0.35)
    assert hit.sum() >= 40


@pytest.mark.parametrize('origin', [(0.1, -0.2, 0.05), (2.0, 0.5, 0.1), (-1.0, 2.0, 0.4)])
def test_agrees_with_ode_for_a_scan_from_one_origin(origin):
    """A lidar-like fan from one origin (the azimuth-culled path), some origins inside
    shapes, with and without a minimum range."""
    import ode   # Debian's python3-pyode: missing = broken install
    shapes = _ode_scene()
    rc = make(shapes)
    yaw = np.linspace(-math.pi, math.pi, 181)
    pitch = np.repeat([-0.3, 0.0, 0.2], len(yaw))
    yaw = np.tile(yaw, 3)
    dirs = np.stack([np.cos(pitch) * np.cos(yaw), np.cos(pitch) * np.sin(yaw), np.sin(pitch)],
                    axis=1)
    for min_range in (0.0, 0.12, 0.5):
        hit = _check_against_ode(ode, rc, shapes, np.array(origin), dirs, 5.0, min_range)
        assert hit.sum() >= 150


def test_one_origin_path_equals_the_per_ray_path_on_a_dense_scan():
    """The azimuth culling must not lose rays: a 0.1 degree fan (axis-aligned boxes, whose
    bounds are exact, boxes across the +-pi direction and under the origin, meshes) gives
    the same hits as the per-ray BVH walk and dense tests."""
    rng = np.random.default_rng(3)
    v, f = uv_sphere(0.4, 8, 16)
    shapes = [box('floor', (6, 6, 0.1), (0, 0, -0.3)),
              box('behind', (0.3, 2.0, 1.0), (-2.0, 0.0, 0.0)),
              box('corner', (0.5, 0.5, 1.0), (-1.5, -1.5, 0.0), (0, 0, 0.3))]
    for i in range(12):
        xyz = rng.uniform(-3, 3, 3) * (1, 1, 0.1)
        if np.linalg.norm(xyz[:2]) < 0.7:
            continue
        if i % 3 == 0:
            shapes.append(box('b%d' % i, rng.uniform(0.1, 0.8, 3), xyz))
        elif i % 3 == 1:
            shapes.append(shape('c%d' % i, Geometry('cylinder', radius=0.2, length=0.8),
                                Pose(xyz)))
        else:
            shapes.append(shape('m%d' % i, Geometry('mesh', vertices=v, faces=f), Pose(xyz)))
    rc = make(shapes)
    yaw = np.tile(np.linspace(-math.pi, math.pi, 3601), 3)
    pitch = np.repeat([-0.05, 0.0, 0.1], 3601)
    dirs = np.stack([np.cos(pitch) * np.cos(yaw), np.cos(pitch) * np.sin(yaw), np.sin(pitch)],
                    axis=1)
    c = np.array([0.05, -0.02, 0.1])
    fan_t, fan_k = rc.cast_hits(c, dirs, 4.0, min_range=0.1)
    origins = np.tile(c, (len(dirs), 1))
    origins[-1, 0] += 1e-9                  # not one origin: the per-ray path
    ray_t, ray_k = rc.cast_hits(origins, dirs, 4.0, min_range=0.1)
    assert np.isfinite(fan_t).sum() > 4000
    np.testing.assert_array_equal(fan_k[:-1], ray_k[:-1])
    np.testing.assert_allclose(fan_t[:-1], ray_t[:-1], atol=1e-9, rtol=0)


def test_shapes_of_one_moving_link_follow_it():
    """Shapes sharing a link (its bound pose method, as the physics hands them out) are posed
    from one call per cast, each with its own local offset and rotation."""
    class Link:
        pose_now = Pose.from_xyz_rpy((2, 0, 0), (0, 0, 0))
        calls = 0

        def pose(self):
            Link.calls += 1
            return Link.pose_now

    link = Link()
    v, f = box_mesh((0.2, 0.2, 0.2))
    shapes = [shape('a', Geometry('box', size=(0.2, 0.2, 0.2)), link_pose=link.pose,
                    local=Pose((0, 1, 0)), model='bot', link='base'),
              shape('b', Geometry('cylinder', radius=0.1, length=0.4), link_pose=link.pose,
                    local=Pose.from_xyz_rpy((0, -1, 0), (math.pi / 2, 0, 0)),
                    model='bot', link='base'),
              shape('c', Geometry('sphere', radius=0.1), link_pose=link.pose,
                    local=Pose((1, 0, 0)), model='bot', link='base'),
              shape('d', Geometry('mesh', vertices=v, faces=f), link_pose=link.pose,
                    local=Pose((0, 0, 1)), model='bot', link='base')]
    rc = make(shapes)
    Link.pose_now = Pose.from_xyz_rpy((0, 0, 0), (0, 0, math.pi / 2))   # turned left
    Link.calls = 0
    d = rc.cast(np.zeros(3), RING, 10.0)
    # local +Y box is now at world -X, the lying cylinder (local -Y, axis along local -Y) lies
    # along world X at x = 1, the sphere (local +X) is at world +Y
    np.testing.assert_allclose(d, [0.8, 0.9, 0.9, np.inf], atol=1e-12)
    assert Link.calls <= 2                  # once per cast per group (solids, mesh)
    Link.pose_now = Pose((0, 0, 5))
    d = rc.cast([0, 0, 6], RING, 10.0)      # inside the mesh box (local z = 1): leaves at 0.1
    np.testing.assert_allclose(d, [0.1, 0.1, 0.1, 0.1], atol=1e-12)
