"""The diploma's chassis mesh package://space_scanner_simulation/meshes/base.dae: a COLLADA file
that assimp (the library RViz loads meshes with) imports with the platform's size and the
description's colours, referenced by chassi_bot.urdf.xacro as the diploma prints it, and drawn
by RViz when the diploma's own command shows the model:
  roslaunch urdf_tutorial display.launch model:='$(find space_scanner_simulation)/urdf/chassi_bot.urdf.xacro'
"""
import os
import re
import subprocess
import xml.etree.ElementTree as ET

import pytest

from my_robot_model import model_check as mc
from course_testing import Proc
from course_testing.gui_check import keep, wait_for_colours

PKG = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DAE = os.path.join(PKG, 'meshes', 'base.dae')
XACRO = os.path.join(PKG, 'urdf', 'chassi_bot.urdf.xacro')
URL = 'package://space_scanner_simulation/meshes/base.dae'
NS = {'c': 'http://www.collada.org/2005/11/COLLADASchema'}


def assimp_info(path):
    r = subprocess.run(['assimp', 'info', path], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, 'assimp info %s failed: %s' % (path, r.stderr or r.stdout)
    return r.stdout


def extents(info):
    def point(name):
        m = re.search(r'%s point\s+\(([-0-9.e]+) ([-0-9.e]+) ([-0-9.e]+)\)' % name, info)
        assert m, 'no "%s point" in assimp info:\n%s' % (name, info)
        return [float(v) for v in m.groups()]
    return point('Minimum'), point('Maximum')


def test_base_dae_is_collada_that_assimp_loads_with_the_platforms_size():
    root = ET.parse(DAE).getroot()
    assert root.tag == '{%s}COLLADA' % NS['c']
    assert root.find('c:asset/c:unit', NS).get('meter') == '1'
    assert root.find('c:asset/c:up_axis', NS).text == 'Z_UP'
    info = assimp_info(DAE)
    assert int(re.search(r'Meshes:\s+(\d+)', info).group(1)) >= 8     # 3 decks, 4 standoffs, battery
    for name in ('deck_green', 'brass', 'battery_grey'):
        assert "'%s'" % name in info, name
    lo, hi = extents(info)
    # assimp turns a Z_UP file to its own y-up frame (x, z, -y); RViz drops that rotation
    size = [hi[0] - lo[0], hi[2] - lo[2], hi[1] - lo[1]]
    assert size == pytest.approx([0.26, 0.15, 0.068], abs=1e-4)
    # the top deck's upper face 100 mm above the ground (base_link is 32.5 mm up)
    assert 0.0325 + hi[1] == pytest.approx(0.0985, abs=0.002)


def test_mesh_materials_are_the_descriptions_colours():
    effects = {}
    root = ET.parse(DAE).getroot()
    for mat in root.iterfind('.//c:library_materials/c:material', NS):
        fx = mat.find('c:instance_effect', NS).get('url').lstrip('#')
        effects[mat.get('name')] = fx
    colours = {}
    for eff in root.iterfind('.//c:library_effects/c:effect', NS):
        d = eff.find('.//c:diffuse/c:color', NS)
        colours[eff.get('id')] = tuple(round(float(v), 3) for v in d.text.split()[:3])
    desc = mc.material_colours(mc.expand_xacro(os.path.join(
        mc.rospack_resolver()('package://space_scanner_description/urdf'), 'chassi_bot.urdf.xacro')))
    for name in ('deck_green', 'brass', 'battery_grey'):
        assert colours[effects[name]] == tuple(round(v, 3) for v in desc[name][:3]), name


def test_generator_writes_the_same_mesh(tmp_path):
    """scripts/make_base_mesh.py reproduces the committed file (but for its time stamps)."""
    out = tmp_path / 'base.dae'
    r = subprocess.run(['/usr/bin/python3', os.path.join(PKG, 'scripts', 'make_base_mesh.py'), str(out)],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    strip = lambda t: re.sub(r'<(created|modified)>[^<]*<', '<\\1><', t)   # noqa: E731
    assert strip(out.read_text()) == strip(open(DAE).read())


def test_simulation_xacro_uses_the_mesh_and_passes_check_urdf():
    m = mc.checked_model(XACRO, root='base_footprint')      # check_urdf + meshes resolved
    meshes = [g.get('filename') for g in m.xml.iter('mesh')]
    assert meshes == [URL]
    assert m.links['base_link'].find('visual/geometry/mesh') is not None
    # the diploma's names
    assert [j for j in m.moving_joints()] == ['wheel_%d_joint' % i for i in range(4)]
    for link in ('base_link', 'upper_link', 'laser_link', 'imu_link', 'base_footprint'):
        assert link in m.links, link
    # the mesh draws the decks: no box visual of its own on the upper decks
    assert m.links['upper_link'].find('visual') is None
    # chassis_mesh:=false: the description's boxes, no mesh
    boxes = mc.expand_xacro(XACRO, args=['chassis_mesh:=false'])
    assert '<mesh' not in boxes and mc.parse(boxes).links['upper_link'].find('visual') is not None


def test_ode_sim_reads_the_mesh_z_up():
    """The simulator's URDF reader loads base.dae as base_link's visual, in base_link's frame."""
    import numpy as np
    from ode_sim.description import urdf
    m = urdf.parse_urdf(mc.expand_xacro(XACRO), XACRO, 'robot')
    assert m.warnings == []
    [mesh] = [v.geometry for link in m.links for v in link.visuals if v.geometry.kind == 'mesh']
    assert mesh.filename == DAE
    assert np.allclose(mesh.vertices.min(axis=0), [-0.13, -0.075, -0.002])
    assert np.allclose(mesh.vertices.max(axis=0), [0.13, 0.075, 0.066])


COLOURS = {'green decks (the mesh)': (0.1, 0.75, 0.2, 1.0), 'red front wheels': (0.85, 0.05, 0.05, 1.0),
           'blue rear wheels': (0.05, 0.2, 0.85, 1.0)}


def test_rviz_draws_the_mesh_with_the_diplomas_command(rviz_env, screen, tmp_path):
    """The diploma's figure 1.9 command, as printed (urdf_tutorial's view: the robot is small in
    it, hence the low pixel threshold); the decks are green only if RViz loaded base.dae (with
    the mesh, no other visual of the model is green)."""
    p = Proc(['roslaunch', 'urdf_tutorial', 'display.launch',
              'model:=$(find space_scanner_simulation)/urdf/chassi_bot.urdf.xacro'],
             env=rviz_env, log=str(tmp_path / 'launch.log'))
    shot = str(tmp_path / 'space_scanner_chassis_mesh_rviz.png')
    try:
        try:
            box, counts = wait_for_colours(screen.display, shot, COLOURS, min_fraction=0.0005)
        except AssertionError as e:
            raise AssertionError('%s\nlaunch log tail:\n%s' % (e, p.output()[-3000:]))
        finally:
            if os.path.exists(shot):
                keep(shot, 'space_scanner_chassis_mesh_rviz.png')
    finally:
        p.stop()
    area = (box[2] - box[0] + 1) * (box[3] - box[1] + 1)
    # the three decks seen from above-front: far more green than either pair of wheels
    green = counts['green decks (the mesh)']
    assert green > 2 * counts['red front wheels'] and green > 0.003 * area, counts
