"""The worlds (worlds/*.world): well-formed, only existing models, ODE physics, the textbook's
parameters, furniture placed clear of walls and of the spawn area; and the SDF loader
(ode_sim.description.sdf) reads every world and every model of the library as they are meant."""
import glob
import importlib.util
import math
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np
import pytest

PKG = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODELS = os.path.join(PKG, 'models')
WORLDS = os.path.join(PKG, 'worlds')
sys.path.insert(0, os.path.join(PKG, 'src'))

from ode_sim.description.resolve import ModelPaths  # noqa: E402
from ode_sim.description.sdf import load_world, parse_sdf_model  # noqa: E402
from ode_sim.description.transforms import Pose  # noqa: E402

_spec = importlib.util.spec_from_file_location('make_models',
                                               os.path.join(PKG, 'scripts', 'make_models.py'))
mm = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(mm)
OBJECTS = {o.name: o for o in mm.objects()}
ROOMS = {r.name: r for r in mm.rooms()}

WORLD_FILES = sorted(os.path.basename(p) for p in glob.glob(os.path.join(WORLDS, '*.world')))
PATHS = ModelPaths([MODELS])


def floats(text):
    return [float(v) for v in text.split()]


def world_el(name):
    root = ET.parse(os.path.join(WORLDS, name)).getroot()
    assert root.tag == 'sdf'
    return root, root.find('world')


def includes(name):
    """[(uri model name, instance name, Pose)] of the <include>s of a world."""
    _, w = world_el(name)
    out = []
    for inc in w.findall('include'):
        model = inc.findtext('uri').strip()[len('model://'):]
        pose = Pose.parse(inc.findtext('pose')) if inc.find('pose') is not None else Pose()
        out.append((model, (inc.findtext('name') or model).strip(), pose))
    return out


def test_all_worlds_present():
    assert set(WORLD_FILES) >= {'empty.world', 'empty_room.world', 'office.world', 'maze.world',
                                'objects.world', 'textbook.world'}


@pytest.mark.parametrize('name', WORLD_FILES)
def test_world_well_formed_and_refers_to_existing_models(name):
    root, w = world_el(name)
    assert root.get('version') == ('1.4' if name == 'textbook.world' else '1.6')
    assert w is not None and w.get('name') == 'default'
    phys = w.find('physics')
    assert phys is not None and phys.get('type') == 'ode'
    uris = [u.text.strip() for u in w.iter('uri')]
    assert 'model://sun' in uris and 'model://ground_plane' in uris
    for uri in uris:
        assert uri.startswith('model://')
        d = os.path.join(MODELS, uri[len('model://'):])
        assert os.path.isfile(os.path.join(d, 'model.config')), uri
        assert os.path.isfile(os.path.join(d, 'model.sdf')), uri
    names = [n for _, n, _ in includes(name)]
    assert len(names) == len(set(names)), 'duplicate model names'


def test_textbook_world_is_the_practical_work_4_world():
    root, w = world_el('textbook.world')
    assert root.get('version') == '1.4'
    scene = w.find('scene')
    assert floats(scene.findtext('ambient')) == [0.4, 0.4, 0.4, 1]
    assert floats(scene.findtext('background')) == [0.7, 0.7, 0.7, 1]
    assert scene.findtext('shadows') == 'true'
    p = w.find('physics')
    assert floats(p.findtext('gravity')) == [0, 0, -9.8]
    assert float(p.findtext('max_step_size')) == 0.001
    assert float(p.findtext('real_time_update_rate')) == 1000
    assert float(p.findtext('real_time_factor')) == 1
    assert p.findtext('ode/solver/type') == 'quick'
    assert int(p.findtext('ode/solver/iters')) == 150
    assert float(p.findtext('ode/solver/sor')) == 1.4
    c = p.find('ode/constraints')
    assert float(c.findtext('cfm')) == 0.00001 and float(c.findtext('erp')) == 0.2
    assert float(c.findtext('contact_max_correcting_vel')) == 1000
    assert float(c.findtext('contact_surface_layer')) == 0.01


def footprint(obj, pose):
    """Corners (4 x 2) of the object's rotated footprint in the world."""
    sx, sy = obj.size[0] / 2, obj.size[1] / 2
    pts = np.array([[-sx, -sy, 0], [sx, -sy, 0], [sx, sy, 0], [-sx, sy, 0]])
    return pose.apply(pts)[:, :2]


def rect_overlap(corners, centre, size):
    """Axis-aligned bounding box of `corners` against a wall box footprint."""
    lo, hi = corners.min(axis=0), corners.max(axis=0)
    wlo, whi = centre[:2] - size[:2] / 2, centre[:2] + size[:2] / 2
    return (lo < whi).all() and (wlo < hi).all()


def office_walls():
    return [(np.array(c), np.array(s)) for _, s, c in ROOMS['office'].boxes()]


def test_office_world_furniture_clear_of_walls_and_spawn_area():
    inc = includes('office.world')
    office = [i for i in inc if i[0] == 'office']
    assert len(office) == 1 and np.allclose(office[0][2].p, 0)
    furniture = [i for i in inc if i[0] in OBJECTS]
    assert len(furniture) >= 6
    assert len({m for m, _, _ in furniture}) >= 6, 'at least 6 different objects'
    walls = office_walls()
    boxes = []
    for model, name, pose in furniture:
        corners = footprint(OBJECTS[model], pose)
        for c, s in walls:
            assert not rect_overlap(corners, c, s), '%s overlaps a wall at %s' % (name, c[:2])
        assert (corners > [-6, -4]).all() and (corners < [6, 4]).all(), name
        # the robot spawn area: 1 m around the origin is free
        lo, hi = corners.min(axis=0), corners.max(axis=0)
        gap = np.maximum(np.maximum(lo, -hi), 0)
        assert np.linalg.norm(gap) >= 1.0, '%s is within 1 m of the origin' % name
        assert abs(pose.p[2]) < 1e-9, '%s does not stand on the floor' % name
        boxes.append((name, lo, hi))
    for i, (n1, lo1, hi1) in enumerate(boxes):       # no two objects in the same place
        for n2, lo2, hi2 in boxes[i + 1:]:
            assert not ((lo1 < hi2).all() and (lo2 < hi1).all()), (n1, n2)


def test_office_world_keeps_doorways_free():
    furniture = [i for i in includes('office.world') if i[0] in OBJECTS]
    for dname, (x, y), axis, width in mm.OFFICE_DOORWAYS:
        along = np.array([1.0, 0.0]) if axis == 'x' else np.array([0.0, 1.0])
        across = along[::-1]
        centre = np.array([x, y])
        corners = np.array([centre + a * 0.8 * along + b * width / 2 * across
                            for a in (-1, 1) for b in (-1, 1)])
        lo, hi = corners.min(axis=0), corners.max(axis=0)
        for model, name, pose in furniture:
            f = footprint(OBJECTS[model], pose)
            assert not ((f.min(axis=0) < hi).all() and (lo < f.max(axis=0)).all()), (dname, name)


def test_objects_world_five_objects_in_front_of_the_origin():
    objs = [i for i in includes('objects.world') if i[0] in OBJECTS]
    assert len(objs) == 5
    assert len({m for m, _, _ in objs}) == 5
    for model, name, pose in objs:
        x, y = pose.p[:2]
        assert 1.5 <= x <= 6, name
        assert abs(math.atan2(y, x)) < math.radians(40), '%s not in front of the origin' % name
        corners = footprint(OBJECTS[model], pose)
        assert corners[:, 0].min() > 1.0, name


def test_maze_world_entrance_ahead_of_the_origin():
    maze = [i for i in includes('maze.world') if i[0] == 'maze']
    assert len(maze) == 1
    assert np.allclose(maze[0][2].p, [1, 0, 0])


# ------------------------------------------------------------------------- the SDF loader

EXPECTED_MODELS = {
    'empty.world': ['ground_plane'],
    'empty_room.world': ['ground_plane', 'empty_room'],
    'maze.world': ['ground_plane', 'maze'],
    'textbook.world': ['ground_plane'],
}


@pytest.mark.parametrize('name', WORLD_FILES)
def test_load_world_parses_every_world(name):
    world = load_world(os.path.join(WORLDS, name), PATHS)
    assert world.warnings == []
    assert [lt.name for lt in world.lights] == ['sun']
    sun = world.lights[0]
    assert sun.type == 'directional' and sun.cast_shadows
    assert np.allclose(sun.direction, (-0.5, 0.1, -0.9))
    assert np.allclose(sun.pose.p, (0, 0, 10))
    assert tuple(world.gravity) == (0.0, 0.0, -9.8)
    names = [m.name for m in world.models]
    assert names == ['ground_plane'] + [n for _, n, _ in includes(name)
                                        if n not in ('sun', 'ground_plane')]
    if name in EXPECTED_MODELS:
        assert names == EXPECTED_MODELS[name]
    ground = world.models[0]
    assert ground.static
    coll = ground.links[0].collisions[0]
    assert coll.geometry.kind == 'plane'
    assert (coll.surface.mu1, coll.surface.mu2) == (100, 50)
    if name == 'textbook.world':
        ph = world.physics
        assert (ph.iters, ph.sor, ph.cfm, ph.erp) == (150, 1.4, 1e-5, 0.2)
        assert (ph.contact_max_correcting_vel, ph.contact_surface_layer) == (1000, 0.01)
        assert (ph.max_step_size, ph.real_time_update_rate) == (0.001, 1000)
    else:
        assert world.physics.iters == 50 and world.physics.sor == 1.3


def test_load_world_office_has_its_walls_and_furniture():
    world = load_world(os.path.join(WORLDS, 'office.world'), PATHS)
    office = next(m for m in world.models if m.name == 'office')
    assert office.static
    colls = [c for link in office.links for c in link.collisions]
    assert len(colls) == len(ROOMS['office'].walls) >= 12
    assert all(c.geometry.kind == 'box' for c in colls)
    assert all(c.geometry.size[2] == pytest.approx(1.0) for c in colls)
    furniture = [m for m in world.models if m.name not in ('ground_plane', 'office')]
    assert len(furniture) >= 6
    for m in furniture:
        assert m.links[0].visuals and all(v.geometry.kind == 'mesh'
                                          for v in m.links[0].visuals)


def test_load_world_objects_has_five_objects_at_their_poses():
    world = load_world(os.path.join(WORLDS, 'objects.world'), PATHS)
    objs = [m for m in world.models if m.name != 'ground_plane']
    assert len(objs) == 5
    for (model, name, pose), m in zip([i for i in includes('objects.world')
                                       if i[0] in OBJECTS], objs):
        assert m.name == name
        assert np.allclose(m.pose.p, pose.p) and np.allclose(np.abs(m.pose.q), np.abs(pose.q))
        assert not m.static
        assert m.links[0].inertial.mass == pytest.approx(OBJECTS[model].mass)


@pytest.mark.parametrize('name', sorted(OBJECTS))
def test_parse_sdf_model_every_object(name):
    path = os.path.join(MODELS, name, 'model.sdf')
    with open(path, 'rb') as f:
        model = parse_sdf_model(f.read(), path, PATHS)
    obj = OBJECTS[name]
    assert model.name == name and model.static == obj.static
    link, = model.links
    assert link.inertial.mass == pytest.approx(obj.mass)
    assert len(link.collisions) == len(obj.collisions)
    assert len(link.visuals) == len(obj.visuals)
    pts = []
    for v, (vname, rgba, _) in zip(link.visuals, obj.visuals):
        assert v.name == vname and v.geometry.kind == 'mesh'
        assert v.geometry.vertices is not None and len(v.geometry.faces) > 0
        assert np.allclose(v.color, rgba, atol=1e-3)
        pts.append(v.pose.apply(v.geometry.vertices))
    pts = np.vstack(pts)
    assert np.allclose(pts.max(axis=0) - pts.min(axis=0), obj.size, atol=0.002)


@pytest.mark.parametrize('name', sorted(ROOMS))
def test_parse_sdf_model_every_room(name):
    path = os.path.join(MODELS, name, 'model.sdf')
    with open(path, 'rb') as f:
        model = parse_sdf_model(f.read(), path, PATHS)
    assert model.static
    colls = [c for link in model.links for c in link.collisions]
    vis = [v for link in model.links for v in link.visuals]
    assert len(colls) == len(vis) == len(ROOMS[name].walls)
    for c in colls:
        assert c.geometry.kind == 'box'
        assert c.geometry.size[2] == pytest.approx(ROOMS[name].height)


def test_every_object_rests_upright_on_the_ground():
    """All 14 objects on the ground plane, 1 s of ODE physics: none sinks, slides or tips."""
    from ode_sim.description.model import World
    from ode_sim.engine.physics import PhysicsWorld
    world = load_world(os.path.join(WORLDS, 'empty.world'), PATHS)
    pw = PhysicsWorld(world.physics, world.gravity)
    pw.add_model(world.models[0])
    for k, name in enumerate(sorted(OBJECTS)):
        path = os.path.join(MODELS, name, 'model.sdf')
        with open(path, 'rb') as f:
            model = parse_sdf_model(f.read(), path, PATHS)
        model.pose = Pose.from_xyz_rpy([3.0 * (k % 5), 3.0 * (k // 5), 0.0], [0, 0, 0])
        pw.add_model(model)
    start = {n: m.pose().p.copy() for n, m in pw.models.items()}
    pw.step(1000)
    assert isinstance(world, World)
    for n, m in pw.models.items():
        p = m.pose()
        assert np.linalg.norm(p.p - start[n]) < 0.01, '%s moved' % n
        assert np.degrees(np.abs(p.rpy()[:2])).max() < 1.0, '%s tipped' % n
