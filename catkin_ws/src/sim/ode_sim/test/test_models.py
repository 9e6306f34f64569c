"""The model library (models/): well-formed Gazebo-layout models, deterministic meshes that are
closed and as large as declared, primitives for collisions and meshes for visuals, an office
whose doorways are open and a maze that can be solved. No roscore needed."""
import importlib.util
import math
import os
import sys
import xml.etree.ElementTree as ET

import numpy as np
import pytest

PKG = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODELS = os.path.join(PKG, 'models')
sys.path.insert(0, os.path.join(PKG, 'src'))

from ode_sim.description import meshgen  # noqa: E402


def _load_script():
    spec = importlib.util.spec_from_file_location('make_models',
                                                  os.path.join(PKG, 'scripts', 'make_models.py'))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


mm = _load_script()
OBJECTS = {o.name: o for o in mm.objects()}
ROOMS = {r.name: r for r in mm.rooms()}
MODEL_NAMES = sorted(d for d in os.listdir(MODELS) if os.path.isdir(os.path.join(MODELS, d)))
REQUIRED = ['table', 'chair', 'bookshelf', 'sofa', 'door_frame', 'trash_bin', 'traffic_cone',
            'barrel', 'box_pallet', 'potted_plant', 'office_desk', 'cabinet']


def floats(text):
    return [float(v) for v in text.split()]


def sdf_root(name):
    return ET.parse(os.path.join(MODELS, name, 'model.sdf')).getroot()


def resolve_uri(uri):
    assert uri.startswith('model://'), uri
    return os.path.join(MODELS, uri[len('model://'):])


def all_files(root):
    out = set()
    for d, _, files in os.walk(root):
        for f in files:
            out.add(os.path.relpath(os.path.join(d, f), root))
    return out


def test_library_has_everything():
    for name in REQUIRED + ['ground_plane', 'sun', 'empty_room', 'office', 'maze']:
        assert name in MODEL_NAMES, name
    assert len(OBJECTS) >= 12
    assert set(MODEL_NAMES) == set(OBJECTS) | set(ROOMS) | {'ground_plane', 'sun'}


@pytest.mark.parametrize('name', MODEL_NAMES)
def test_model_config_and_sdf_well_formed(name):
    cfg = ET.parse(os.path.join(MODELS, name, 'model.config')).getroot()
    assert cfg.tag == 'model'
    assert cfg.findtext('name').strip() == name
    assert cfg.findtext('version').strip()
    sdf = cfg.find('sdf')
    assert sdf.get('version') == '1.6'
    assert os.path.isfile(os.path.join(MODELS, name, sdf.text.strip()))
    assert cfg.find('author/name').text.strip()
    assert cfg.findtext('description').strip()
    root = sdf_root(name)
    assert root.tag == 'sdf' and root.get('version') == '1.6'
    for uri in root.iter('uri'):
        assert os.path.isfile(resolve_uri(uri.text.strip())), (name, uri.text)
    if name != 'sun':
        model = root.find('model')
        assert model.get('name') == name
        for tag in ('collision', 'visual'):
            names = [e.get('name') for e in model.iter(tag)]
            assert len(names) == len(set(names)), 'duplicate %s names in %s' % (tag, name)


def test_regenerating_gives_identical_files(tmp_path):
    mm.generate(str(tmp_path))
    ours, fresh = all_files(MODELS), all_files(str(tmp_path))
    assert ours == fresh
    for rel in sorted(ours):
        with open(os.path.join(MODELS, rel), 'rb') as a, open(str(tmp_path / rel), 'rb') as b:
            assert a.read() == b.read(), '%s differs from a fresh generation' % rel


def test_meshgen_detects_open_and_flipped_meshes():
    cube = meshgen.box((1, 1, 1))
    tri = cube.triangles()
    assert meshgen.edge_balance(tri) == 0
    assert meshgen.edge_balance(tri[1:]) > 0                 # a missing triangle
    flipped = tri.copy()
    flipped[0] = flipped[0][::-1]
    assert meshgen.edge_balance(flipped) > 0                 # one face wound the wrong way
    assert meshgen.signed_volume(tri) == pytest.approx(1.0)
    with pytest.raises(ValueError):
        meshgen.lathe([(0, 0), (1, 0), (0, 1)], segments=10)


def test_composite_inertia_of_one_box_is_the_box_formula():
    com, inertia = meshgen.composite_inertia(12.0, [('box', (1, 2, 3), (1, 2, 3), (0, 0, 0), 1)])
    assert np.allclose(com, (1, 2, 3))
    assert np.allclose(inertia, np.diag([13, 10, 5]))
    # two equal boxes side by side = one box twice as long
    com, inertia = meshgen.composite_inertia(2.0, [('box', (1, 1, 1), (-0.5, 0, 0), (0, 0, 0), 1),
                                                   ('box', (1, 1, 1), (0.5, 0, 0), (0, 0, 0), 1)])
    assert np.allclose(com, 0)
    assert np.allclose(inertia, np.diag([2 / 12 * 2, 2 / 12 * 5, 2 / 12 * 5]))


STLS = sorted((n, f) for n in OBJECTS for f in os.listdir(os.path.join(MODELS, n, 'meshes')))


@pytest.mark.parametrize('name,stl_file', STLS)
def test_stl_closed_and_consistent(name, stl_file):
    from stl import mesh
    m = mesh.Mesh.from_file(os.path.join(MODELS, name, 'meshes', stl_file),
                            calculate_normals=False)
    tri = m.vectors.astype(float)
    assert len(tri) > 0
    assert meshgen.edge_balance(tri) == 0, 'open or inconsistently wound mesh'
    volume, _, _ = m.get_mass_properties()
    assert volume > 1e-7
    assert meshgen.signed_volume(tri) > 0                    # wound outwards
    cross = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    area2 = np.linalg.norm(cross, axis=1)
    ok = area2 > 1e-9
    unit = cross[ok] / area2[ok, None]
    stored = m.normals[ok].astype(float)
    assert np.allclose(np.linalg.norm(stored, axis=1), 1.0, atol=1e-4)
    assert (np.einsum('ij,ij->i', unit, stored) > 0.99).all(), 'stored normals disagree'


@pytest.mark.parametrize('name', sorted(OBJECTS))
def test_object_meshes_have_the_declared_size(name):
    from stl import mesh
    obj = OBJECTS[name]
    d = os.path.join(MODELS, name, 'meshes')
    pts = np.vstack([mesh.Mesh.from_file(os.path.join(d, f)).vectors.reshape(-1, 3)
                     for f in sorted(os.listdir(d))])
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    assert np.allclose(hi - lo, obj.size, atol=0.002), (hi - lo, obj.size)
    assert abs(lo[2]) < 1e-6, 'object does not stand on z = 0'
    assert np.allclose((lo[:2] + hi[:2]) / 2, 0, atol=0.02), 'footprint not centred'
    assert sum(mesh.Mesh.from_file(os.path.join(d, f)).vectors.shape[0]
               for f in os.listdir(d)) < 2000
    assert 0.5 <= obj.mass <= 200


@pytest.mark.parametrize('name', sorted(OBJECTS))
def test_object_sdf_visuals_are_meshes_collisions_primitives(name):
    obj = OBJECTS[name]
    model = sdf_root(name).find('model')
    assert (model.findtext('static') == 'true') == obj.static
    link, = model.findall('link')
    visuals = link.findall('visual')
    assert visuals
    for v in visuals:
        uri = v.find('geometry/mesh/uri')
        assert uri is not None, '%s visual %s is not a mesh' % (name, v.get('name'))
        assert uri.text.endswith('.stl')
        assert len(floats(v.findtext('material/ambient'))) == 4
        assert len(floats(v.findtext('material/diffuse'))) == 4
    half = np.array(obj.size) / 2
    for c in link.findall('collision'):
        geom = c.find('geometry')[0]
        assert geom.tag in ('box', 'cylinder', 'sphere'), (name, geom.tag)
        xyz = np.array(floats(c.findtext('pose'))[:3])
        if geom.tag == 'box':
            ext = np.array(floats(geom.findtext('size'))) / 2
        elif geom.tag == 'cylinder':
            r, ln = float(geom.findtext('radius')), float(geom.findtext('length'))
            ext = np.array([r, r, ln / 2])
        else:
            ext = np.full(3, float(geom.findtext('radius')))
        rpy = floats(c.findtext('pose'))[3:]
        if any(rpy):    # tilted box: its bounding box
            from ode_sim.description.transforms import Pose
            rot = np.abs(Pose.from_xyz_rpy([0, 0, 0], rpy).matrix()[:3, :3])
            ext = rot @ ext
        lo, hi = xyz - ext, xyz + ext
        assert (lo[:2] >= -half[:2] - 0.01).all() and (hi[:2] <= half[:2] + 0.01).all(), c.get(
            'name')
        assert lo[2] >= -1e-6 and hi[2] <= obj.size[2] + 0.01, c.get('name')
    inertial = link.find('inertial')
    assert float(inertial.findtext('mass')) == pytest.approx(obj.mass)
    i = {t: float(inertial.findtext('inertia/' + t))
         for t in ('ixx', 'ixy', 'ixz', 'iyy', 'iyz', 'izz')}
    tensor = np.array([[i['ixx'], i['ixy'], i['ixz']], [i['ixy'], i['iyy'], i['iyz']],
                       [i['ixz'], i['iyz'], i['izz']]])
    ev = np.linalg.eigvalsh(tensor)
    assert (ev > 0).all()
    assert ev[0] + ev[1] >= ev[2] * 0.999                    # triangle inequality
    com = np.array(floats(inertial.findtext('pose'))[:3])
    assert (np.abs(com[:2]) <= half[:2]).all() and 0 < com[2] < obj.size[2]


def test_ground_plane_and_sun_as_gazebo():
    link = sdf_root('ground_plane').find('model/link')
    assert sdf_root('ground_plane').findtext('model/static') == 'true'
    plane = link.find('collision/geometry/plane')
    assert floats(plane.findtext('normal')) == [0, 0, 1]
    assert floats(link.findtext('collision/surface/friction/ode/mu')) == [100]
    assert floats(link.findtext('collision/surface/friction/ode/mu2')) == [50]
    assert floats(link.findtext('visual/geometry/plane/size')) == [100, 100]
    light = sdf_root('sun').find('light')
    assert light.get('type') == 'directional' and light.get('name') == 'sun'
    assert light.findtext('cast_shadows') == 'true'
    assert floats(light.findtext('pose')) == [0, 0, 10, 0, 0, 0]
    assert floats(light.findtext('diffuse'))[:3] == [0.8, 0.8, 0.8]
    assert floats(light.findtext('specular'))[:3] == [0.2, 0.2, 0.2]
    assert floats(light.findtext('direction')) == [-0.5, 0.1, -0.9]
    assert float(light.findtext('attenuation/range')) == 1000


# ------------------------------------------------------------------------- rooms

def wall_boxes(name):
    """(centre xyz, size xyz) of every wall collision box of a room model, from its SDF."""
    model = sdf_root(name).find('model')
    assert model.findtext('static') == 'true'
    out = []
    for c in model.iter('collision'):
        size = c.find('geometry/box/size')
        assert size is not None, 'walls are boxes'
        pose = floats(c.findtext('pose'))
        assert pose[3:] == [0, 0, 0]
        out.append((np.array(pose[:3]), np.array(floats(size.text))))
    visuals = list(model.iter('visual'))
    assert len(visuals) == len(out)
    for v in visuals:
        assert v.find('geometry/box') is not None and v.find('material/diffuse') is not None
    return out


def segment_hits_box(p, q, centre, size, margin=0.0):
    """Does the 2-D segment p-q cross the footprint of a box (grown by margin)?"""
    lo = centre[:2] - size[:2] / 2 - margin
    hi = centre[:2] + size[:2] / 2 + margin
    p, q = np.asarray(p, float), np.asarray(q, float)
    d = q - p
    t0, t1 = 0.0, 1.0
    for k in range(2):
        if abs(d[k]) < 1e-12:
            if p[k] < lo[k] or p[k] > hi[k]:
                return False
            continue
        a, b = (lo[k] - p[k]) / d[k], (hi[k] - p[k]) / d[k]
        a, b = min(a, b), max(a, b)
        t0, t1 = max(t0, a), min(t1, b)
        if t0 > t1:
            return False
    return True


def hits_any(p, q, walls, margin=0.0):
    return any(segment_hits_box(p, q, c, s, margin) for c, s in walls)


def test_segment_box_helper():
    c, s = np.array([0.0, 0.0, 0.5]), np.array([1.0, 0.1, 1.0])
    assert segment_hits_box((0, -1), (0, 1), c, s)
    assert not segment_hits_box((0.6, -1), (0.6, 1), c, s)
    assert not segment_hits_box((-1, 0.2), (1, 0.2), c, s)
    assert segment_hits_box((-1, 0.0), (-0.49, 0.0), c, s)


def test_empty_room():
    walls = wall_boxes('empty_room')
    assert len(walls) == 4
    for c, s in walls:
        assert s[2] == pytest.approx(1.0) and min(s[:2]) == pytest.approx(0.1)
    lo = np.min([c[:2] - s[:2] / 2 for c, s in walls], axis=0)
    hi = np.max([c[:2] + s[:2] / 2 for c, s in walls], axis=0)
    assert np.allclose(hi - lo, [6.1, 6.1])
    # closed: no way out from the centre in any direction
    for a in np.linspace(0, 2 * math.pi, 36, endpoint=False):
        assert hits_any((0, 0), (5 * math.cos(a), 5 * math.sin(a)), walls)


def test_office_size_and_spawn_room():
    walls = wall_boxes('office')
    lo = np.min([c[:2] - s[:2] / 2 for c, s in walls], axis=0)
    hi = np.max([c[:2] + s[:2] / 2 for c, s in walls], axis=0)
    assert np.allclose(hi - lo, [12.1, 8.1])
    # the origin is in a room: enclosed, and 1 m clear of every wall
    for c, s in walls:
        assert not segment_hits_box((-1, 0), (1, 0), c, s, margin=0.0)
        assert not segment_hits_box((0, -1), (0, 1), c, s, margin=0.0)
        gap = np.maximum(np.abs(c[:2]) - s[:2] / 2, 0)
        assert np.linalg.norm(gap) >= 1.0
    assert hits_any((0, 0), (0, -10), walls) and hits_any((-10, 0), (0, 0), walls)
    assert hits_any((0, 0), (10, 0), walls)


@pytest.mark.parametrize('doorway', mm.OFFICE_DOORWAYS, ids=lambda d: d[0])
def test_office_doorways_are_open(doorway):
    walls = wall_boxes('office')
    name, (x, y), axis, width = doorway
    assert width >= 0.9
    along = np.array([1.0, 0.0]) if axis == 'x' else np.array([0.0, 1.0])
    across = np.array([along[1], along[0]])
    centre = np.array([x, y])
    # straight lines through the doorway, from one room into the other, at its middle and
    # 0.45 m to either side (a 0.9 m wide passage), touch no wall
    for off in (-0.44, 0.0, 0.44):
        p = centre + off * across - 0.8 * along
        q = centre + off * across + 0.8 * along
        assert not hits_any(p, q, walls), '%s: a wall across the doorway at %+.2f' % (name, off)
    # and it is an opening in a wall: a line along the wall through it meets walls both sides
    assert hits_any(centre, centre + (width / 2 + 0.2) * across, walls)
    assert hits_any(centre, centre - (width / 2 + 0.2) * across, walls)
    # the passage leads somewhere: 0.8 m beyond the wall on both sides is free floor
    for side in (-1, 1):
        p = centre + side * 0.8 * along
        assert not hits_any(p - 0.3 * across, p + 0.3 * across, walls)


def test_office_rooms_connected_through_doorways():
    """Rooms A, B, C, D, the corridor and outside: the doorways join them into one graph."""
    rooms = {'A': (-6, -4, -2, 2), 'B': (-2, -4, 2, 2), 'C': (2, -4, 6, 2),
             'D': (3.5, 2, 6, 4), 'corridor': (-6, 2, 3.5, 4)}

    def where(pt):
        for n, (x0, y0, x1, y1) in rooms.items():
            if x0 < pt[0] < x1 and y0 < pt[1] < y1:
                return n
        return 'outside'

    edges = set()
    for name, (x, y), axis, _ in mm.OFFICE_DOORWAYS:
        along = np.array([0.5, 0.0]) if axis == 'x' else np.array([0.0, 0.5])
        a, b = where(np.array([x, y]) - along), where(np.array([x, y]) + along)
        assert a != b, name
        edges.add(frozenset((a, b)))
    seen, todo = {'B'}, ['B']
    while todo:
        n = todo.pop()
        for e in edges:
            if n in e:
                for m in e - {n}:
                    if m not in seen:
                        seen.add(m)
                        todo.append(m)
    assert seen == set(rooms) | {'outside'}
    assert len(rooms) - 1 >= 3 and 'corridor' in rooms


def test_maze_is_5x5_and_solvable():
    walls = wall_boxes('maze')
    for c, s in walls:
        assert s[2] == pytest.approx(0.5)
    lo = np.min([c[:2] - s[:2] / 2 for c, s in walls], axis=0)
    hi = np.max([c[:2] + s[:2] / 2 for c, s in walls], axis=0)
    assert np.allclose(lo, [-0.05, -2.55]) and np.allclose(hi, [5.05, 2.55])

    def centre(r, c):            # row 0 is the south row
        return np.array([c + 0.5, r - 2.0])

    def open_between(a, b):
        return not hits_any(a, b, walls)

    start, goal = (2, 0), (2, 4)
    assert open_between(np.array([-0.5, 0.0]), centre(*start)), 'no entrance'
    assert open_between(centre(*goal), np.array([5.5, 0.0])), 'no exit'
    seen, todo = {start}, [start]
    while todo:
        r, c = todo.pop()
        for dr, dc in ((1, 0), (-1, 0), (0, 1), (0, -1)):
            n = (r + dr, c + dc)
            if 0 <= n[0] < 5 and 0 <= n[1] < 5 and n not in seen \
                    and open_between(centre(r, c), centre(*n)):
                seen.add(n)
                todo.append(n)
    assert goal in seen
    assert len(seen) == 25, 'every cell of the maze is reachable'
    # and it is a maze: the straight line from the entrance to the exit is blocked
    assert hits_any(np.array([-0.5, 0.0]), np.array([5.5, 0.0]), walls)
    # no other openings in the outer wall
    for r in range(5):
        for c, (a, b) in ((0, (-0.5, 0.5)), (4, (4.5, 5.5))):
            if r != 2:
                assert hits_any(np.array([a, r - 2.0]), np.array([b, r - 2.0]), walls)


def test_readme_lists_every_model():
    with open(os.path.join(MODELS, 'README.md')) as f:
        text = f.read()
    for name in MODEL_NAMES:
        assert '`%s`' % name in text
    assert 'make_models.py' in text
