"""Where a spawned model lands, without ROS (description/spawning.py, sdf.parse_sdf_model,
urdf.parse_urdf): gazebo_ros_api_plugin's composition of initial_pose with the model's own
<pose>, checked against ignition::math's Pose3d operator+ written out here independently
(quaternions as (w, x, y, z) in the sandwich product, as ignition writes them)."""
import math
import random

import numpy as np
import pytest

from ode_sim.description import sdf, urdf, walls
from ode_sim.description.resolve import ModelPaths
from ode_sim.description.spawning import initial_in_world, spawn_pose
from ode_sim.description.transforms import Pose


# ---------------------------------------------------------------- ignition::math, written out

def hamilton(a, b):
    """(w, x, y, z) product a * b."""
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return (aw * bw - ax * bx - ay * by - az * bz,
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw)


def wxyz(pose):
    x, y, z, w = pose.q
    return (w, x, y, z)


def ign_plus(a, b):
    """ignition Pose3d a + b: p = b.p + b.q (0, a.p) b.q^-1 (CoordPositionAdd),
    q = b.q * a.q (CoordRotationAdd). Returns (p, q as (w, x, y, z))."""
    bq = wxyz(b)
    inv = (bq[0], -bq[1], -bq[2], -bq[3])
    t = hamilton(bq, hamilton((0.0,) + tuple(a.p), inv))
    return np.array(b.p) + np.array(t[1:]), hamilton(bq, wxyz(a))


def same(pose, p, q_wxyz, tol=1e-12):
    w, x, y, z = q_wxyz
    return (np.allclose(pose.p, p, atol=tol)
            and abs(abs(float(np.dot(pose.q, (x, y, z, w)))) - 1.0) < tol)


def random_pose(rng):
    return Pose.from_xyz_rpy([rng.uniform(-5, 5) for _ in range(3)],
                             [rng.uniform(-3, 3) for _ in range(3)])


# ---------------------------------------------------------------------------- the arithmetic

def test_initial_pose_composed_with_the_models_own_pose():
    own = Pose.from_xyz_rpy((1, 0, 0), (0, 0, math.pi / 2))
    initial = Pose.from_xyz_rpy((10, 0, 0), (0, 0, math.pi / 2))
    got = spawn_pose(initial, own)
    # the own pose is relative to the initial pose: 1 m along the initial pose's x (world y)
    assert got.p == pytest.approx([10, 1, 0], abs=1e-12)
    assert abs(got.rpy()[2]) == pytest.approx(math.pi, abs=1e-12)
    # the other order would put it at (1, 10, 0)
    assert not np.allclose((own * initial).p, got.p)
    assert same(got, *ign_plus(own, initial))


def test_spawn_pose_is_ignitions_model_pose_plus_initial_pose():
    rng = random.Random(7)
    for _ in range(200):
        own, initial = random_pose(rng), random_pose(rng)
        assert same(spawn_pose(initial, own), *ign_plus(own, initial), tol=1e-9)
    assert same(spawn_pose(initial), initial.p, wxyz(initial))            # no own pose
    assert same(spawn_pose(initial, Pose()), initial.p, wxyz(initial))    # identity own pose


def test_reference_frame_as_spawn_sdf_model():
    """xyz = frame.q xyz + frame.p; q = initial_q * frame.q (ignition `initial_q *=
    frame_pose.Rot()`), then + the model pose."""
    rng = random.Random(11)
    for _ in range(100):
        own, initial, frame = random_pose(rng), random_pose(rng), random_pose(rng)
        fq = wxyz(frame)
        inv = (fq[0], -fq[1], -fq[2], -fq[3])
        p = np.array(frame.p) + np.array(hamilton(fq, hamilton((0.0,) + tuple(initial.p),
                                                               inv))[1:])
        q = hamilton(wxyz(initial), fq)
        assert same(initial_in_world(initial, frame), p, q, tol=1e-9)
        start = Pose(p, (q[1], q[2], q[3], q[0]))
        assert same(spawn_pose(initial, own, frame), *ign_plus(own, start), tol=1e-9)
    # the rotation order differs from frame * initial when the rotations do not commute
    frame = Pose.from_xyz_rpy((0, 0, 0), (0, 0, math.pi / 2))
    initial = Pose.from_xyz_rpy((0, 0, 0), (math.pi / 2, 0, 0))
    assert not same(initial_in_world(initial, frame), (0, 0, 0), wxyz(frame * initial), 1e-6)
    # and agrees with it for two yaws
    initial = Pose.from_xyz_rpy((1, 2, 3), (0, 0, 0.4))
    got = initial_in_world(initial, frame)
    assert same(got, (frame * initial).p, wxyz(frame * initial), 1e-12)
    assert same(initial_in_world(initial, None), initial.p, wxyz(initial))


# ------------------------------------------------------------------ the SDF forms of a spawn

BOX = ('<link name="link"><inertial><mass>1</mass></inertial><collision name="c"><geometry>'
       '<box><size>1 1 1</size></box></geometry></collision></link>')


@pytest.fixture
def paths(tmp_path):
    """A model path with model://posed_box, whose model.sdf has its own <pose>."""
    d = tmp_path / 'models' / 'posed_box'
    d.mkdir(parents=True)
    (d / 'model.config').write_text('<model><name>posed box</name>'
                                    '<sdf version="1.6">model.sdf</sdf></model>')
    (d / 'model.sdf').write_text('<sdf version="1.6"><model name="posed_box">'
                                 '<pose>5 5 5 0 0 0</pose>%s</model></sdf>' % BOX)
    return ModelPaths(env={'GAZEBO_MODEL_PATH': str(tmp_path / 'models'),
                           'HOME': str(tmp_path / 'home'), 'GAZEBO_MODEL_DATABASE_URI': ''})


def test_sdf_model_own_pose_and_name():
    text = ('<sdf version="1.6"><model name="old"><pose>1 2 3 0 0 0.5</pose>%s</model></sdf>'
            % BOX)
    m = sdf.parse_sdf_model(text, '<test>', name='new')
    assert m.name == 'new' and m.include_uri == ''
    assert same(m.pose, (1, 2, 3), wxyz(Pose.from_xyz_rpy((0, 0, 0), (0, 0, 0.5))))
    bare = sdf.parse_sdf_model('<model name="b">%s</model>' % BOX, '<test>', name='b2')
    assert bare.name == 'b2' and same(bare.pose, (0, 0, 0), (1, 0, 0, 0))


@pytest.mark.parametrize('text', [
    # gazebo_ros spawn_model -database, exactly as it sends it
    '<sdf version="1.4">\n    <world name="default">\n        <include>\n'
    '            <uri>model://posed_box</uri>\n        </include>\n    </world>\n</sdf>',
    '<sdf version="1.6"><include><uri>model://posed_box</uri></include></sdf>',
    '<include><uri>model://posed_box</uri></include>',
])
def test_include_without_pose_has_the_identity(paths, text):
    """gazebo_ros writes initial_pose into the include as its <pose>, which replaces the
    included file's own <pose> (5 5 5 here): the model lands at initial_pose."""
    m = sdf.parse_sdf_model(text, '<test>', paths, name='crate_1')
    assert m.name == 'crate_1' and m.include_uri == 'model://posed_box'
    assert same(m.pose, (0, 0, 0), (1, 0, 0, 0))
    initial = Pose.from_xyz_rpy((1, 2, 0), (0, 0, 0.3))
    assert same(spawn_pose(initial, m.pose), initial.p, wxyz(initial))


@pytest.mark.parametrize('wrap', [
    '<sdf version="1.4"><world name="default">%s</world></sdf>',
    '<sdf version="1.6">%s</sdf>',
])
def test_include_pose_composed(paths, wrap):
    inc = ('<include><uri>model://posed_box</uri><name>ignored</name>'
           '<pose>0 1 0 0 0 0</pose></include>')
    m = sdf.parse_sdf_model(wrap % inc, '<test>', paths, name='crate_2')
    assert m.name == 'crate_2' and m.include_uri == 'model://posed_box'
    assert same(m.pose, (0, 1, 0), (1, 0, 0, 0))
    got = spawn_pose(Pose.from_xyz_rpy((3, 0, 0), (0, 0, math.pi / 2)), m.pose)
    assert got.p == pytest.approx([2, 0, 0], abs=1e-12)


def test_world_include_of_a_light(paths):
    """<sdf><world><include> of model://sun is a light, as <sdf><include> was."""
    text = '<sdf version="1.4"><world name="default"><include><uri>model://sun</uri>' \
           '</include></world></sdf>'
    light = sdf.parse_sdf_light(text, '<test>', paths, name='sun_2')
    assert light is not None and light.name == 'sun_2'
    assert sdf.parse_sdf_light('<sdf><world name="w"><include><uri>model://posed_box</uri>'
                               '</include></world></sdf>', '<test>', paths) is None


def test_no_spawnable_element_is_one_line():
    with pytest.raises(sdf.ModelError, match=r'no <model>, <include> or <light> in the SDF'):
        sdf.parse_sdf_model('<sdf version="1.6"><world name="w"/></sdf>', '<test>')


# ---------------------------------------------------------------------------------- URDF

ROBOT = ('<robot name="r">%s<link name="base"><inertial><mass value="1"/><inertia ixx="0.1" '
         'ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial><collision><geometry>'
         '<box size="1 1 1"/></geometry></collision></link></robot>')


def test_urdf_robot_origin_is_the_own_pose():
    m = urdf.parse_urdf(ROBOT % '<origin xyz="1 2 3" rpy="0 0 0.5"/>', '<test>', 'bot')
    assert same(m.pose, (1, 2, 3), wxyz(Pose.from_xyz_rpy((0, 0, 0), (0, 0, 0.5))))
    plain = urdf.parse_urdf(ROBOT % '', '<test>', 'bot')
    assert same(plain.pose, (0, 0, 0), (1, 0, 0, 0))       # an ordinary URDF: initial_pose


# --------------------------------------------------------------------------------- walls

def test_walls_land_where_drawn_with_an_identity_initial_pose():
    """The wall tool's model has the identity as its own pose, so spawned with an identity
    initial_pose (as both windows do) each wall stays on its segment, under either rule."""
    segs = [(0, 0, 4, 0), (4, 0, 4, 3)]
    m = sdf.parse_sdf_model(walls.walls_model('walls_1', segs), '<test>', name='walls_1')
    assert same(m.pose, (0, 0, 0), (1, 0, 0, 0))
    world = spawn_pose(Pose(), m.pose)
    centres = sorted(tuple(np.round((world * m.links[0].pose * c.pose).p, 9))
                     for c in m.links[0].collisions)
    assert centres == [(2.0, 0.0, 1.25), (4.0, 1.5, 1.25)]
