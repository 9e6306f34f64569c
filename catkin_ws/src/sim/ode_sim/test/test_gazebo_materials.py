"""What the camera sees of Gazebo-style models: COLLADA effects with a <texture>, MTL colours and
map_Kd, OGRE material scripts named by <script><uri>model://.../materials/scripts</uri>, the
Gazebo/... names, SDF colours; a missing texture or an unknown material is a warning and a
plain colour, never a world that does not load."""
import math
import os

import numpy as np
import pytest

from ode_sim.description import sdf
from ode_sim.description.model import Light
from ode_sim.description.resolve import ModelPaths
from ode_sim.description.transforms import Pose
from ode_sim.engine.physics import PhysicsWorld
from ode_sim.engine.render import Renderer, focal_length

HERE = os.path.dirname(os.path.abspath(__file__))
MODELS = os.path.join(HERE, 'fixtures', 'gazebo_models')
W, H, HFOV = 160, 120, math.radians(60)
LIGHT = Light('sun', direction=(1.0, 0.2, -1.0), diffuse=(0.8, 0.8, 0.8, 1),
              specular=(0.1, 0.1, 0.1, 1))


def world(body, tmp_path=None):
    return sdf.parse_world('<sdf version="1.6"><world name="w">%s</world></sdf>' % body,
                           os.path.join(str(tmp_path or HERE), 'w.world'),
                           paths=ModelPaths.only([MODELS]))


def shoot(w, eye, look_x=True):
    pw = PhysicsWorld(w.physics, w.gravity)
    for m in w.models:
        pw.add_model(m)
    r = Renderer(W, H, HFOV)
    try:
        r.set_scene(pw.visual_shapes(), lights=[LIGHT], ambient=(0.4, 0.4, 0.4, 1),
                    background=(0.7, 0.7, 0.7, 1))
        rgb, _ = r.render(Pose(eye))
    finally:
        r.release()
    return rgb.astype(int)


def pixel(eye, point):
    """(row, col) where the camera at `eye` looking along +X sees world `point`."""
    f = focal_length(W, HFOV)
    d = np.subtract(point, eye)
    return (int(round((H - 1) / 2 - f * d[2] / d[0])), int(round((W - 1) / 2 - f * d[1] / d[0])))


def patch(rgb, rc, k=2):
    r, c = rc
    return rgb[r - k:r + k + 1, c - k:c + k + 1].reshape(-1, 3).mean(axis=0)


def test_collada_texture_and_effect_colour():
    w = world('<include><uri>model://step_block</uri></include>')
    assert not w.warnings
    eye = (-2.0, 0.0, 0.4)
    rgb = shoot(w, eye)
    # the upper step's face at x = 0: the texture's left half (green) at y > 0, right (blue)
    g = patch(rgb, pixel(eye, (0.0, 0.25, 0.42)))
    b = patch(rgb, pixel(eye, (0.0, -0.25, 0.42)))
    assert g[1] > 100 and g[1] > 2 * g[0] and g[1] > 2 * g[2], g
    assert b[2] > 100 and b[2] > 2 * b[0] and b[2] > 2 * b[1], b
    # the lower step's top: the <phong> red
    red = patch(rgb, pixel(eye, (-0.25, 0.0, 0.2)))
    assert red[0] > 100 and red[0] > 3 * red[1] and red[0] > 3 * red[2], red


def test_ogre_material_script_with_texture():
    w = world('<include><uri>model://painted_panel</uri></include>')
    assert not w.warnings
    vis = w.models[0].links[0].visuals[0]
    assert vis.material.name == 'Panel/Stripes' and vis.material.texture.endswith('stripes.png')
    assert vis.material.specular == pytest.approx((0.1, 0.1, 0.1))      # from its parent
    eye = (-2.0, 0.0, 0.5)
    rgb = shoot(w, eye)
    top = patch(rgb, pixel(eye, (-0.05, 0.0, 0.8)))          # yellow: the image's top half
    bottom = patch(rgb, pixel(eye, (-0.05, 0.0, 0.2)))       # magenta
    assert top[0] > 100 and top[1] > 100 and top[2] < 0.3 * top[0], top
    assert bottom[0] > 100 and bottom[2] > 100 and bottom[1] < 0.3 * bottom[0], bottom


def test_obj_mtl_texture():
    w = world('<include><uri>model://prism</uri></include>')
    eye = (-1.0, 0.0, 0.25)
    rgb = shoot(w, eye)
    o = patch(rgb, pixel(eye, (1.5, 0.0, 0.25)))      # the apex edge at x = 1 faces the camera
    assert o[0] > 120 and o[0] > o[1] > o[2] + 30, o       # orange


def test_sdf_colours_and_gazebo_names(tmp_path):
    body = '''<model name="a"><static>true</static><pose>0 0.6 0.5 0 0 0</pose><link name="l">
      <visual name="v"><geometry><box><size>0.1 1 1</size></box></geometry>
      <material><script><uri>file://media/materials/scripts/gazebo.material</uri>
      <name>Gazebo/Blue</name></script></material></visual></link></model>
      <model name="b"><static>true</static><pose>0 -0.6 0.5 0 0 0</pose><link name="l">
      <visual name="v"><geometry><box><size>0.1 1 1</size></box></geometry>
      <material><ambient>0 0.5 0 1</ambient><diffuse>0 1 0 1</diffuse></material>
      </visual></link></model>'''
    w = world(body, tmp_path)
    assert not w.warnings
    eye = (-2.0, 0.0, 0.5)
    rgb = shoot(w, eye)
    blue = patch(rgb, pixel(eye, (-0.05, 0.6, 0.5)))
    green = patch(rgb, pixel(eye, (-0.05, -0.6, 0.5)))
    assert blue[2] > 100 and blue[0] < 30 and blue[1] < 30, blue
    assert green[1] > 100 and green[0] < 30 and green[2] < 30, green


def test_unknown_material_and_missing_texture_warn_and_draw_plain(tmp_path):
    scripts = tmp_path / 'scripts'
    scripts.mkdir()
    (scripts / 'x.material').write_text(
        'material X/Missing\n{\n technique\n {\n  pass\n  {\n   diffuse 0 0 1 1\n'
        '   texture_unit\n   {\n    texture gone.png\n   }\n  }\n }\n}\n')
    body = '''<model name="a"><static>true</static><pose>0 0.6 0.5 0 0 0</pose><link name="l">
      <visual name="v"><geometry><box><size>0.1 1 1</size></box></geometry>
      <material><script><uri>file://%s</uri><name>X/Missing</name></script></material>
      </visual></link></model>
      <model name="b"><static>true</static><pose>0 -0.6 0.5 0 0 0</pose><link name="l">
      <visual name="v"><geometry><box><size>0.1 1 1</size></box></geometry>
      <material><script><uri>file://%s</uri><name>X/Nope</name></script></material>
      </visual></link></model>''' % (scripts, scripts)
    w = world(body, tmp_path)
    assert len(w.warnings) == 2, w.warnings
    tex, unknown = w.warnings
    assert "material 'X/Missing': texture 'gone.png' not found" in tex and '\n' not in tex
    assert str(scripts / 'x.material') in tex
    assert "unknown material 'X/Nope'" in unknown and 'drawn grey' in unknown
    eye = (-2.0, 0.0, 0.5)
    rgb = shoot(w, eye)
    blue = patch(rgb, pixel(eye, (-0.05, 0.6, 0.5)))          # its plain diffuse colour
    grey = patch(rgb, pixel(eye, (-0.05, -0.6, 0.5)))
    assert blue[2] > 100 and blue[0] < 30, blue
    assert abs(grey[0] - grey[1]) < 5 and abs(grey[1] - grey[2]) < 5 and grey[0] > 60, grey


def test_broken_material_script_is_a_warning(tmp_path):
    scripts = tmp_path / 'scripts'
    scripts.mkdir()
    (scripts / 'bad.material').write_text('material Broken\n{\n technique\n {\n')
    w = world('''<model name="a"><static>true</static><link name="l"><visual name="v">
      <geometry><box><size>1 1 1</size></box></geometry>
      <material><script><uri>file://%s</uri><name>Broken</name></script></material>
      </visual></link></model>''' % scripts, tmp_path)
    assert len(w.warnings) == 1 and '\n' not in w.warnings[0], w.warnings
    assert '%s:3: block "technique" is not closed' % (scripts / 'bad.material') \
        in w.warnings[0]
    assert "material 'Broken' drawn in a plain colour" in w.warnings[0]


def test_urdf_collada_visual_keeps_its_materials_unless_gazebo_paints_it():
    from ode_sim.description.urdf import parse_urdf
    dae = os.path.join(MODELS, 'step_block', 'meshes', 'step_block.dae')
    urdf = '''<robot name="r"><link name="base"><inertial><mass value="1"/>
      <inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
      <visual><geometry><mesh filename="file://%s"/></geometry>
      <material name="white"><color rgba="1 1 1 1"/></material></visual></link>%s</robot>'''
    plain = parse_urdf(urdf % (dae, ''), os.path.join(HERE, 'r.urdf'), 'r')
    v = plain.links[0].visuals[0]
    assert v.material is None and [p.material.name for p in v.geometry.parts] == ['red', 'split']
    painted = parse_urdf(urdf % (dae, '<gazebo reference="base"><material>Gazebo/Blue</material>'
                                 '</gazebo>'), os.path.join(HERE, 'r.urdf'), 'r')
    v = painted.links[0].visuals[0]
    assert v.material.name == 'Gazebo/Blue' and v.material.diffuse == (0.0, 0.0, 1.0, 1.0)


def test_scene_markers_colour_a_collada_model_by_its_materials():
    from ode_sim.ros.markers import shape_marker
    w = world('<include><uri>model://step_block</uri></include>')
    pw = PhysicsWorld(w.physics, w.gravity)
    for m in w.models:
        pw.add_model(m)
    (shape,) = [s for s in pw.visual_shapes() if s.model == 'step_block']
    mk = shape_marker(shape, 0, 'odom', None)
    assert len(mk.colors) == len(mk.points) == 2 * 12 * 3
    red = mk.colors[0]
    assert (red.r, red.g, red.b) == pytest.approx((0.8, 0.0, 0.0), abs=1e-6)
    tex = mk.colors[-1]                    # white x the texture's mean: half green, half blue
    assert tex.r == pytest.approx(0.0) and tex.g == pytest.approx(100 / 255, abs=0.01) and \
        tex.b == pytest.approx(100 / 255, abs=0.01)


def test_collada_transparency_is_blended(tmp_path):
    """The red <phong> made half transparent (<transparent opaque="A_ONE"> white,
    <transparency> 0.5): seen from the side against a blue background the lower step is a mix
    of its red and the blue behind it; opaque it hides the blue."""
    import shutil
    model = tmp_path / 'glass_block'
    shutil.copytree(os.path.join(MODELS, 'step_block'), str(model))
    dae = model / 'meshes' / 'step_block.dae'
    dae.write_text(dae.read_text().replace(
        '<shininess><float>20</float></shininess>',
        '<shininess><float>20</float></shininess><transparent opaque="A_ONE"><color>1 1 1 1'
        '</color></transparent><transparency><float>0.5</float></transparency>'))
    (model / 'model.sdf').write_text((model / 'model.sdf').read_text().replace(
        'model://step_block', 'model://glass_block'))
    eye = (-0.25, 3.0, 0.1)
    pose = Pose.from_xyz_rpy(eye, (0.0, 0.0, -math.pi / 2))

    def look(models_dir, name):
        w = sdf.parse_world('<sdf version="1.6"><world name="w"><include><uri>model://%s</uri>'
                            '</include></world></sdf>' % name, str(tmp_path / 'w.world'),
                            paths=ModelPaths.only([models_dir]))
        pw = PhysicsWorld(w.physics, w.gravity)
        for m in w.models:
            pw.add_model(m)
        r = Renderer(W, H, HFOV)
        try:
            r.set_scene(pw.visual_shapes(), lights=[LIGHT], ambient=(0.4, 0.4, 0.4, 1),
                        background=(0.0, 0.0, 1.0, 1))
            rgb, _ = r.render(pose)
        finally:
            r.release()
        return rgb.astype(int)[H // 2 - 2:H // 2 + 3, W // 2 - 2:W // 2 + 3].reshape(-1, 3).mean(0)

    opaque = look(MODELS, 'step_block')
    glass = look(str(tmp_path), 'glass_block')
    assert opaque[0] > 60 and opaque[2] < 10, opaque            # ambient-lit red side
    assert 25 < glass[0] < opaque[0] - 20 and glass[2] > 100, glass   # half red, half blue
