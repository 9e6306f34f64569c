"""ode_sim.description.urdf: URDF -> model as Gazebo spawns it (fixed-joint lumping, kinematics, <gazebo>
extensions, transmissions), the course's three robots, and one-line errors for bad input."""
import math
import os
import shutil
import subprocess

import numpy as np
import pytest

from ode_sim.description import materials
from ode_sim.description.model import ModelError
from ode_sim.description.transforms import Pose
from ode_sim.description.urdf import load_urdf, parse_urdf

HERE = os.path.dirname(os.path.abspath(__file__))
FIX = os.path.join(HERE, 'fixtures', 'loaders')
URDF = os.path.join(FIX, 'urdf')
BAD = os.path.join(FIX, 'bad')
SRC = os.path.abspath(os.path.join(HERE, '..', '..', '..'))     # catkin_ws/src


def rz(a):
    return Pose.from_xyz_rpy((0, 0, 0), (0, 0, a)).rotation()


# ------------------------------------------------------------------ lumping maths

def test_two_link_fixed_chain_lumped():
    m = load_urdf(os.path.join(URDF, 'two_link_fixed.urdf'), 'tl')
    assert [l.name for l in m.links] == ['base'] and m.joints == []
    base = m.links[0]
    i = base.inertial
    assert i.mass == pytest.approx(3.0)
    assert np.allclose(i.pose.p, [1 / 3, 0, 0])
    # base inertia diag(1,2,3) in a frame rolled 90 deg -> diag(1,3,2) in the link frame;
    # tool diag(.1,.2,.3) yawed 90 deg -> diag(.2,.1,.3); parallel axis: 2*(1/3)^2 + 1*(2/3)^2
    # = 2/3 on y and z
    got = i.pose.rotation() @ i.tensor() @ i.pose.rotation().T
    assert np.allclose(got, np.diag([1.2, 3.1 + 2 / 3, 2.3 + 2 / 3]), atol=1e-12)
    # lumped frames
    assert set(base.lumped) == {'tool', 'marker'}
    assert np.allclose(base.lumped['tool'].p, [1, 0, 0])
    assert np.allclose(base.lumped['tool'].rotation(), rz(math.pi / 2))
    assert np.allclose(base.lumped['marker'].p, [1, 0, 0.2])
    # collisions re-posed, names as Gazebo's, <gazebo reference="tool"> only on tool's
    own, tip = base.collisions
    assert own.name == 'base_collision' and own.surface.mu1 == 1.0
    assert tip.name == 'base_fixed_joint_lump__tip_collision_1'
    assert np.allclose(tip.pose.p, [1, 0.5, 0])             # (0.5,0,0) turned 90 deg
    s = tip.surface
    assert (s.mu1, s.mu2, s.kp, s.kd, s.max_vel, s.min_depth) == (0.3, 0.4, 1e5, 5, 0.2, 0.003)
    assert s.fdir1 == (0, 1, 0)
    tool_vis, marker_vis = base.visuals
    assert tool_vis.color == materials.GAZEBO_MATERIALS['Gazebo/Blue']
    assert tool_vis.material_name == 'Gazebo/Blue'
    assert marker_vis.color == materials.GREY and np.allclose(marker_vis.pose.p, [1, 0, 0.2])
    # sensor of the lumped, massless marker: attached to base with the pose composed
    [imu] = base.sensors
    assert imu.link == 'base' and imu.type == 'imu'
    assert np.allclose(imu.pose.p, [1, 0, 0.3])
    assert imu.params['noise_stddev'] == 0.002
    assert imu.params['linear_acceleration_noise_stddev'] == 0.02
    assert m.warnings == []


def test_lumped_inertia_matches_point_cloud():
    """Independent check: sample both bodies as point clouds with the given inertia and compare
    the total about the common COM."""
    m = load_urdf(os.path.join(URDF, 'two_link_fixed.urdf'), 'tl')
    i = m.links[0].inertial

    def cloud(mass, diag, pose):
        # six point masses on the principal axes reproduce a diagonal inertia
        a, b, c = diag
        # I_xx = 2 m/6 (y^2+z^2) terms: solve for squared half-extents
        ex2 = 3 * (b + c - a) / (2 * mass)
        ey2 = 3 * (a + c - b) / (2 * mass)
        ez2 = 3 * (a + b - c) / (2 * mass)
        pts = []
        for k, e2 in enumerate((ex2, ey2, ez2)):
            for sgn in (1, -1):
                p = np.zeros(3)
                p[k] = sgn * math.sqrt(e2)
                pts.append(p)
        return [(mass / 6, pose.apply(p)) for p in pts]

    base = cloud(2, (1, 2, 3), Pose.from_xyz_rpy((0, 0, 0), (math.pi / 2, 0, 0)))
    tool = cloud(1, (0.1, 0.2, 0.3), Pose.from_xyz_rpy((1, 0, 0), (0, 0, math.pi / 2)))
    pts = base + tool
    mass = sum(w for w, _ in pts)
    com = sum(w * p for w, p in pts) / mass
    t = sum(w * (np.dot(p - com, p - com) * np.eye(3) - np.outer(p - com, p - com))
            for w, p in pts)
    assert mass == pytest.approx(i.mass)
    assert np.allclose(com, i.pose.p)
    assert np.allclose(t, i.pose.rotation() @ i.tensor() @ i.pose.rotation().T)


# ------------------------------------------------------------------ kinematics

def test_rotated_chain_kinematics():
    m = load_urdf(os.path.join(URDF, 'chain.urdf'), 'chain')
    assert [l.name for l in m.links] == ['base', 'l1', 'l2', 'l3']
    assert m.canonical_link == 'base' and 'mid' in m.link('base').lumped
    l1, l2 = m.link('l1'), m.link('l2')
    assert np.allclose(l1.pose.p, [1, 0, 0.5])
    assert np.allclose(l1.pose.rotation(), rz(math.pi / 2))
    assert np.allclose(l2.pose.p, [0, 0, 0.5])            # (0,1,0) in l1 = (-1,0,0)
    j1, j2, j3 = m.joints
    assert (j1.name, j1.type, j1.parent, j1.child) == ('j1', 'revolute', 'base', 'l1')
    assert np.allclose(j1.anchor, [1, 0, 0.5]) and np.allclose(j1.axis, [0, 1, 0])
    assert (j1.lower, j1.upper, j1.effort, j1.velocity) == (-1, 1, 10, 2)
    assert (j1.damping, j1.friction) == (0.7, 0.1)
    # origin re-parented onto the surviving link: mount (z 0.5) * j1 origin
    assert np.allclose(j1.origin.p, [1, 0, 0.5])
    assert np.allclose((m.link('base').pose * j1.origin).matrix(), l1.pose.matrix())
    assert (j2.type, j2.parent) == ('prismatic', 'l1')
    assert np.allclose(j2.anchor, [0, 0, 0.5]) and np.allclose(j2.axis, [1, 0, 0])
    assert (j2.lower, j2.upper) == (0, 0.3)
    assert j3.type == 'continuous' and np.allclose(j3.axis, l2.pose.rotate([1, 0, 0]))
    assert j3.lower is None and j3.effort is None
    assert any('<mimic> is ignored' in w and "'j3'" in w for w in m.warnings)


def test_world_root_fixes_the_model():
    m = load_urdf(os.path.join(URDF, 'world_root.urdf'), 'arm')
    assert [l.name for l in m.links] == ['pedestal', 'upper']
    fix, shoulder = m.joints
    assert (fix.type, fix.parent, fix.child) == ('fixed', 'world', 'pedestal')
    assert np.allclose(m.link('pedestal').pose.p, [0, 0, 0.3])
    assert shoulder.parent == 'pedestal' and np.allclose(shoulder.anchor, [0, 0, 0.5])
    assert m.canonical_link == 'pedestal'


# ------------------------------------------------------------------ <gazebo>, transmissions

def test_gazebo_extensions():
    path = os.path.join(URDF, 'gazebo_ext.urdf')
    m = load_urdf(path, 'ext')
    assert m.name == 'ext' and m.source == path and '<robot name="ext_bot"' in m.urdf
    assert [l.name for l in m.links] == ['base_footprint', 'camera', 'bumper', 'left_wheel']
    bf = m.link('base_footprint')
    assert set(bf.lumped) == {'base_link', 'laser'}
    assert np.allclose(bf.lumped['laser'].p, [0.05, 0, 0.2])
    # meshes: package:// and relative to the URDF file
    mesh_col = bf.collisions[0]
    assert mesh_col.geometry.kind == 'mesh'
    assert mesh_col.geometry.filename == os.path.join(FIX, 'meshes', 'cube_ascii.stl')
    assert np.allclose(mesh_col.geometry.vertices.max(axis=0), [0.1, 0.1, 0.05])
    assert np.allclose(mesh_col.pose.p, [0, 0, 0.1])
    vis = bf.visuals
    assert vis[0].geometry.kind == 'mesh' and vis[0].color == (0, 0, 0.8, 1)
    assert vis[1].color == (1, 0, 0, 1) and vis[2].color == (1, 0, 0, 1)  # named later
    # laser: lumped; its <gazebo reference> applies to its collision and its sensor
    laser_col = bf.collisions[1]
    assert laser_col.surface.mu1 == 0.9 and mesh_col.surface.mu1 == 1.0
    [ray] = bf.sensors
    assert ray.type == 'ray' and ray.link == 'base_footprint' and ray.update_rate == 40
    assert np.allclose(ray.pose.p, [0.05, 0, 0.22])
    assert np.allclose(ray.pose.rotation(), rz(math.pi))
    assert ray.params['samples'] == 720 and ray.params['range_max'] == 30
    assert ray.plugins[0].params['frameName'] == 'laser'
    # camera: kept by disableFixedJointLumping, bumper by preserveFixedJoint
    cam_joint, bumper_joint, wheel_joint = m.joints
    assert (cam_joint.type, cam_joint.parent, cam_joint.child) == \
        ('fixed', 'base_footprint', 'camera')
    assert bumper_joint.child == 'bumper' and bumper_joint.type == 'fixed'
    cam = m.link('camera')
    assert np.allclose(cam.pose.p, [0.1, 0, 0.1])
    assert cam.visuals[0].color == (1, 0, 0, 1) and cam.visuals[0].material_name == 'Gazebo/Red'
    assert cam.sensors[0].params['width'] == 800 and cam.sensors[0].link == 'camera'
    wheel = m.link('left_wheel')
    assert wheel.self_collide and not wheel.gravity
    assert wheel.collisions[0].surface.bounce == 0.5
    assert np.allclose(wheel_joint.axis, [0, 1, 0])      # z turned by roll -90 deg
    assert np.allclose(wheel_joint.anchor, [0, 0.1, 0.1])
    # model plugins and static
    assert [p.filename for p in m.plugins] == ['libgazebo_ros_diff_drive.so',
                                               'libgazebo_ros_control.so']
    assert m.plugins[0].params['leftJoint'] == 'left_wheel_joint' and not m.static
    # transmissions
    t1, t2 = m.transmissions
    assert t1.type == 'transmission_interface/SimpleTransmission'
    assert t1.joints == {'left_wheel_joint': ['EffortJointInterface']}
    assert t1.actuators == {'left_motor': 30.0}
    assert t2.joints == {'left_wheel_joint': ['VelocityJointInterface']}
    assert any("Deprecated syntax, please prepend 'hardware_interface/' to "
               "'VelocityJointInterface'" in w for w in m.warnings)
    assert any("no_such_link" in w for w in m.warnings)
    assert all(w.startswith(path + ':') for w in m.warnings)


def test_links_without_inertial_as_gazebo():
    path = os.path.join(URDF, 'no_inertial.urdf')
    m = load_urdf(path, 'p')
    assert [l.name for l in m.links] == ['base_footprint']
    bf = m.links[0]
    assert bf.inertial.mass == 1 and np.allclose(bf.inertial.pose.p, [0, 0, 0.05])
    assert set(bf.lumped) == {'base_link', 'frame'} and len(bf.visuals) == 1
    assert m.joints == []
    [w] = m.warnings
    assert "link 'mount' has no <inertial>" in w and 'tip' in w
    assert 'urdf2sdf: link[mount] has no inertia, not modeled in sdf' in w


# ------------------------------------------------------------------ the course's robots

def _xacro(relpath):
    exe = shutil.which('xacro')
    assert exe is not None, 'xacro is not on PATH: the workspace is not built or not sourced (scripts/env.sh)'
    out = subprocess.run([exe, os.path.join(SRC, relpath)], capture_output=True, text=True,
                         timeout=60)
    assert out.returncode == 0, out.stderr
    return out.stdout


@pytest.mark.parametrize('relpath, root, movable', [
    ('course/my_robot_model/urdf/diff_robot_model.urdf.xacro', 'base_link',
     ['wheel_left_joint', 'wheel_right_joint']),
    ('course/jacksonbot_description/urdf/jacksonbot/jacksonbot.urdf.xacro', 'base_footprint',
     ['left_wheel_joint', 'right_wheel_joint']),
    ('space_scanner/space_scanner_description/urdf/chassi_bot.urdf.xacro', 'base_footprint',
     ['wheel_%d_joint' % i for i in range(4)]),
])
def test_repo_robots(relpath, root, movable):
    text = _xacro(relpath)
    m = parse_urdf(text, os.path.join(SRC, relpath), 'robot')
    assert m.canonical_link == root and m.links[0].name == root
    assert [j.name for j in m.joints] == movable
    for j in m.joints:
        assert j.type == 'continuous' and j.parent == root
        assert np.allclose(j.axis, [0, 1, 0])
        assert np.allclose(m.link(j.child).pose.p, j.anchor)
    for link in m.links:
        assert link.inertial.mass > 0 and link.collisions
    if 'chassi_bot' in relpath:
        assert len(m.transmissions) == 4
        assert m.transmissions[0].joints == {'wheel_0_joint': ['VelocityJointInterface']}
        assert m.link(root).lumped.keys() >= {'laser', 'camera_link', 'imu_link'}
        total = 0.6 + 0.15 + 0.15 + 0.17 + 0.01 + 0.01
        assert m.link(root).inertial.mass == pytest.approx(total)
    if 'jacksonbot' in relpath:
        casters = [c for c in m.links[0].collisions if 'caster' in c.name]
        assert len(casters) == 2 and all(c.surface.mu1 == 0 for c in casters)
        assert m.link('left_wheel_link').collisions[0].surface.kp == 1e9
    if 'diff_robot' in relpath:
        mesh = [v for v in m.links[0].visuals if v.geometry.kind == 'mesh']
        assert mesh and mesh[0].geometry.filename.endswith('base_frame.stl')


# ------------------------------------------------------------------ bad input

@pytest.mark.parametrize('name, line, words', [
    ('malformed.urdf', 4, ['malformed XML', 'mismatched tag']),
    ('missing_mass.urdf', 2, ["<inertial> of link 'a' needs <mass"]),
    ('missing_box_size.urdf', 2, ['<box> needs a size attribute']),
    ('missing_joint_type.urdf', 3, ["joint name='j'", 'needs a type attribute']),
    ('unknown_link.urdf', 3, ["joint 'j' refers to unknown link 'ghost'"]),
    ('two_roots.urdf', 1, ["2 root links ('a', 'b')"]),
    ('loop.urdf', 7, ['loop', "link 'a' (joint 'j2')"]),
    ('two_parents.urdf', 4, ["link 'c' has two parent joints 'j1' and 'j2'"]),
    ('floating.urdf', 3, ["joint 'free' of type floating is not supported"]),
    ('planar.urdf', 3, ["joint 'flat' of type planar is not supported"]),
    ('no_limit.urdf', 3, ["joint 'elbow' is of type revolute but has no <limit"]),
    ('undefined_material.urdf', 2, ["link 'a' material 'chartreuse' undefined"]),
    ('xacro_left.urdf', 2, ['<xacro:property>', 'expand it with xacro']),
    ('collision_dae.urdf', 2, ['thing.dae', 'cannot read: Collada: File came out empty']),
    ('missing_mesh.urdf', 2, ['package://ode_sim/no/such.stl', 'not found']),
    ('bad_origin.urdf', 3, ["xyz='1 2'", 'expected 3 numbers']),
    ('massless_root.urdf', 2, ["link 'chassis' has zero mass"]),
    ('not_robot.urdf', 1, ['expected <robot>']),
])
def test_bad_urdf_one_line(name, line, words):
    path = os.path.join(BAD, name)
    with pytest.raises(ModelError) as e:
        load_urdf(path, 'bad')
    msg = str(e.value)
    assert '\n' not in msg
    assert msg.startswith('%s:%d: ' % (path, line)), msg
    for w in words:
        assert w in msg, msg


@pytest.mark.parametrize('name, words', [
    ('zero_mass.urdf', ["link 'body' has zero mass"]),
    ('non_pd.urdf', ["link 'body'", 'not positive definite']),
])
def test_bad_mass_refused(name, words):
    path = os.path.join(BAD, name)
    with pytest.raises(ModelError) as e:
        load_urdf(path, 'bad')
    msg = str(e.value)
    assert msg.startswith(path + ': ') and '\n' not in msg
    for w in words:
        assert w in msg, msg


def test_source_name_for_param_text():
    with pytest.raises(ModelError) as e:
        parse_urdf('<robot name="r"><link name="a"></robot>', '/robot_description', 'r')
    assert str(e.value).startswith('/robot_description:1: malformed XML')
