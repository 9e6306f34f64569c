"""Gazebo's own model layout through assimp: COLLADA (unit, up axis, node hierarchy, several
geometries), OBJ + MTL, <scale>, <submesh> with <center>; mesh collisions as ODE trimeshes and
the lidar's rays against the same triangles; bad mesh files give one line naming the file."""
import math
import os

import numpy as np
import pytest

from ode_sim.description import sdf
from ode_sim.description.mesh import load_mesh
from ode_sim.description.model import (Collision, Geometry, Inertial, Link, Model, ModelError,
                                       Surface)
from ode_sim.description.resolve import ModelPaths
from ode_sim.description.transforms import Pose
from ode_sim.engine.physics import PhysicsWorld
from ode_sim.engine.raycast import RayCaster

HERE = os.path.dirname(os.path.abspath(__file__))
MODELS = os.path.join(HERE, 'fixtures', 'gazebo_models')
DAE = os.path.join(MODELS, 'step_block', 'meshes', 'step_block.dae')
OBJ = os.path.join(MODELS, 'prism', 'meshes', 'prism.obj')


def world(models_xml):
    paths = ModelPaths.only([MODELS])
    return sdf.parse_world('<sdf version="1.6"><world name="w">%s</world></sdf>' % models_xml,
                           os.path.join(HERE, 'w.world'), paths=paths)


def box(x, y, z, size=0.2, mass=1.0):
    i = mass * size * size / 6
    return Model('box_%g_%g' % (x, y), pose=Pose((x, y, z)), links=[Link(
        'link', inertial=Inertial(mass, ixx=i, iyy=i, izz=i),
        collisions=[Collision('c', Geometry('box', size=(size,) * 3),
                              surface=Surface(mu1=1, mu2=1))])])


def test_collada_unit_up_axis_hierarchy_and_two_geometries():
    m = load_mesh(DAE)
    # centimetres to metres, Y up to Z up, the block node's translate and each node's own
    assert [(p.node, p.name) for p in m.parts] == [('lower', 'lower_geom'),
                                                   ('upper', 'upper_geom')]
    lo, up = m.parts
    assert np.allclose(lo.positions.min(axis=0), [-0.5, -0.5, 0.0], atol=1e-6)
    assert np.allclose(lo.positions.max(axis=0), [0.0, 0.5, 0.2], atol=1e-6)
    assert np.allclose(up.positions.min(axis=0), [0.0, -0.5, 0.0], atol=1e-6)
    assert np.allclose(up.positions.max(axis=0), [0.5, 0.5, 0.6], atol=1e-6)
    # normals follow the rotation and agree with the winding (counter-clockwise outside)
    for part in m.parts:
        tri = part.positions[part.faces].astype(float)
        fn = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        fn /= np.linalg.norm(fn, axis=1, keepdims=True)
        assert np.allclose(fn, part.normals[part.faces[:, 0]], atol=1e-5)
    assert any(np.allclose(n, [0, 0, 1]) for n in up.normals)
    # the collision arrays are both geometries' triangles, de-duplicated
    assert m.faces.shape == (24, 3) and m.vertices.dtype == np.float64
    # materials: the <phong> colour and the <lambert>'s texture found in ../materials/textures
    assert lo.material.name == 'red' and lo.material.diffuse[:3] == pytest.approx((0.8, 0, 0))
    assert up.material.texture == os.path.join(MODELS, 'step_block', 'materials', 'textures',
                                               'split.png')
    assert up.uvs is not None and up.uvs.shape == (len(up.positions), 2)
    assert not m.warnings


def test_scale_submesh_center_and_cache():
    m = load_mesh(DAE, (2.0, 1.0, 0.5))
    assert np.allclose(m.vertices.max(axis=0), [1.0, 0.5, 0.3], atol=1e-6)
    assert load_mesh(DAE, (2.0, 1.0, 0.5)) is m                  # cached by file and scale
    assert load_mesh(DAE) is not m
    up = load_mesh(DAE, submesh='upper')
    assert len(up.parts) == 1 and np.allclose(up.vertices.min(axis=0), [0, -0.5, 0], atol=1e-6)
    c = load_mesh(DAE, (1, 1, 2), submesh='upper_geom', center=True)
    assert np.allclose(c.vertices.min(axis=0), [-0.25, -0.5, -0.6], atol=1e-6)
    assert np.allclose(c.vertices.max(axis=0), [0.25, 0.5, 0.6], atol=1e-6)
    with pytest.raises(ModelError) as e:
        load_mesh(DAE, submesh='roof')
    assert str(e.value) == ("mesh %s: <submesh> 'roof' not found (the file has: lower, "
                            "lower_geom, upper, upper_geom)" % DAE)


def test_obj_with_mtl():
    m = load_mesh(OBJ)
    assert m.faces.shape == (8, 3)
    assert np.allclose(m.vertices.min(axis=0), [1, -1, 0]) and np.allclose(
        m.vertices.max(axis=0), [2, 1, 0.5])
    mat = m.parts[0].material
    assert mat.name == 'orange' and mat.diffuse[:3] == pytest.approx((0.9, 0.5, 0.1))
    assert mat.texture == os.path.join(MODELS, 'prism', 'meshes', 'orange.png')


def test_sdf_submesh_and_scale_elements():
    w = world("""<model name="m"><static>true</static><link name="l"><collision name="c">
      <geometry><mesh><uri>model://step_block/meshes/step_block.dae</uri>
        <submesh><name>lower</name><center>true</center></submesh><scale>2 2 2</scale>
      </mesh></geometry></collision></link></model>""")
    g = w.models[0].links[0].collisions[0].geometry
    assert g.submesh == 'lower' and g.center
    assert np.allclose(g.vertices.min(axis=0), [-0.5, -1.0, -0.2], atol=1e-6)


def test_box_dropped_on_a_collada_model_rests_on_its_steps():
    """The block's bounding box is 0.6 m high everywhere; its lower step is 0.2 m high."""
    w = world('<include><uri>model://step_block</uri></include>')
    pw = PhysicsWorld(w.physics, w.gravity)
    for m in w.models:
        pw.add_model(m)
    low = pw.add_model(box(-0.25, 0.0, 1.0))
    high = pw.add_model(box(0.25, 0.0, 1.0))
    assert not any('bounding box' in x for m in w.models for x in m.warnings)
    pw.step(2000)
    assert low.pose().p[2] == pytest.approx(0.3, abs=0.005), 'the bounding box gives 0.7'
    assert high.pose().p[2] == pytest.approx(0.7, abs=0.005)


def test_lidar_sees_the_prism_outline_not_its_bounding_box():
    w = world('<include><uri>model://prism</uri></include>')
    pw = PhysicsWorld(w.physics, w.gravity)
    for m in w.models:
        pw.add_model(m)
    angles = np.radians([0.0, 10.0, 20.0, -20.0, 40.0])
    dirs = np.stack([np.cos(angles), np.sin(angles), np.zeros_like(angles)], axis=1)
    for core in ('compiled', 'python'):
        rc = RayCaster(pw.collision_shapes(), core=core) if core == 'python' else \
            RayCaster(pw.collision_shapes())
        t, _ = rc.cast_hits([0.0, 0.0, 0.25], dirs, 10.0)
        # the apex (1, 0) ahead, then the slanted faces x - |y| = 1: r = 1 / (cos - |sin|)
        expect = 1.0 / (np.cos(angles) - np.abs(np.sin(angles)))
        expect[-1] = np.inf                                    # 40 deg passes the prism
        assert np.allclose(t[:4], expect[:4], atol=1e-6), (core, t)
        assert t[2] > 1.0 / math.cos(math.radians(20)) + 0.5   # the bounding box: 1.064
        assert not np.isfinite(t[4]) or t[4] > 9.99


def _bad(tmp_path, name, text):
    p = str(tmp_path / name)
    with open(p, 'w') as f:
        f.write(text)
    with pytest.raises(ModelError) as e:
        load_mesh(p)
    msg = str(e.value)
    assert msg.startswith('mesh %s: ' % p) and '\n' not in msg, msg
    return msg


def test_truncated_collada_is_one_line(tmp_path):
    text = open(DAE).read()
    msg = _bad(tmp_path, 'cut.dae', text[:len(text) // 2])
    assert 'cannot read' in msg


def test_collada_without_triangles_is_one_line(tmp_path):
    msg = _bad(tmp_path, 'empty.dae', """<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><up_axis>Z_UP</up_axis></asset>
  <library_visual_scenes><visual_scene id="s"><node id="n"/></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>""")
    assert 'no triangles' in msg or 'cannot read' in msg


def test_unknown_format_and_not_a_mesh_are_one_line(tmp_path):
    assert 'cannot read' in _bad(tmp_path, 'notes.txt', 'hello\n')
    assert 'cannot read' in _bad(tmp_path, 'x.obj', 'this is not an OBJ file\n')


def test_missing_texture_warns_and_draws_plain(tmp_path):
    text = open(DAE).read().replace('../materials/textures/split.png', 'nowhere.png')
    p = str(tmp_path / 'notex.dae')
    with open(p, 'w') as f:
        f.write(text)
    m = load_mesh(p)
    assert m.parts[1].material.texture == ''
    assert len(m.warnings) == 1 and "texture 'nowhere.png' not found" in m.warnings[0]
    assert p in m.warnings[0] and '\n' not in m.warnings[0]


def test_a_mesh_body_rests_on_a_mesh_model():
    """Trimesh against trimesh (ODE's collider): a dynamic body whose collision is the OBJ
    prism, centred (<submesh><center>) and scaled to 0.4 x 0.8 x 0.2 m, dropped on the upper
    step of the COLLADA block (0.6 m high)."""
    w = world('''<include><uri>model://step_block</uri></include>
      <model name="p"><pose>0.25 0 1.0 0 0 0</pose><link name="l">
        <inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz>
        </inertia></inertial>
        <collision name="c"><geometry><mesh><uri>model://prism/meshes/prism.obj</uri>
          <submesh><name>prism</name><center>true</center></submesh><scale>0.4 0.4 0.4</scale>
        </mesh></geometry></collision></link></model>''')
    pw = PhysicsWorld(w.physics, w.gravity)
    for m in w.models:
        pw.add_model(m)
    pw.step(2500)
    p = pw.models['p'].pose().p
    assert p[2] == pytest.approx(0.7, abs=0.01), p
    assert abs(p[0] - 0.25) < 0.05 and abs(p[1]) < 0.05


def test_the_diplomas_chassis_mesh_loads_and_is_drawn():
    """space_scanner_simulation/meshes/base.dae (COLLADA as assimp exports it) as the chassis
    visual of the simulation's URDF: parsed, spawned, drawn by the camera."""
    import shutil
    import subprocess
    from ode_sim.description.model import Light, Physics
    from ode_sim.description.urdf import parse_urdf
    from ode_sim.engine.render import Renderer
    src = os.path.abspath(os.path.join(HERE, '..', '..', '..'))
    dae = os.path.join(src, 'space_scanner', 'space_scanner_simulation', 'meshes', 'base.dae')
    m = load_mesh(dae)
    assert len(m.parts) >= 2 and all(p.material is not None for p in m.parts)
    size = m.vertices.max(axis=0) - m.vertices.min(axis=0)
    assert 0.05 < size.min() and size.max() < 1.0, size          # metres, a small chassis
    xacro = os.path.join(src, 'space_scanner', 'space_scanner_simulation', 'urdf',
                         'chassi_bot.urdf.xacro')
    out = subprocess.run([shutil.which('xacro'), xacro], capture_output=True, text=True,
                         timeout=60)
    assert out.returncode == 0, out.stderr
    robot = parse_urdf(out.stdout, xacro, 'robot')
    vis = [v for link in robot.links for v in link.visuals
           if v.geometry.kind == 'mesh' and v.geometry.filename == dae]
    assert len(vis) == 1 and vis[0].geometry.parts
    pw = PhysicsWorld(Physics())
    pw.add_model(robot)
    r = Renderer(160, 120, 1.0)
    try:
        r.set_scene(pw.visual_shapes(), lights=[Light('sun', direction=(0.3, 0.5, -1.0))],
                    background=(0.0, 0.0, 0.0, 1))
        rgb, _ = r.render(Pose.from_xyz_rpy((-0.6, 0.0, 0.4), (0.0, 0.55, 0.0)))
    finally:
        r.release()
    assert (rgb.max(axis=2) > 0).mean() > 0.05            # the robot fills part of the image
