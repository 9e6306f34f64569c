"""The compiled core (engine/core, C++ on libode) against the PyODE step loop it replaces: the
same scenes stepped by both give the same trajectories (contacts, friction, bounce, fdir1,
joint motors, position servo, efforts, damping, sleeping models woken by a touch, the space
scanner in the office)."""
import os
import shutil
import subprocess

import numpy as np
import pytest

from ode_sim.description import sdf, urdf
from ode_sim.description.model import (Collision, Geometry, Inertial, Joint, Link, Model,
                                       Physics, Surface)
from ode_sim.description.transforms import Pose
from ode_sim.engine import _core
from ode_sim.engine.compiled import check_layout
from ode_sim.engine.physics import PhysicsWorld

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = os.path.abspath(os.path.join(HERE, '..', '..', '..'))
TOL = 1e-9


def ground(**surface):
    return Model('ground_plane', static=True, links=[Link('link', collisions=[
        Collision('c', Geometry('plane'), surface=Surface(mu1=100, mu2=50, **surface))])])


def box(name, pose, size=(0.4, 0.4, 0.4), mass=1.0, surface=None):
    sx, sy, sz = size
    inertial = Inertial(mass, ixx=mass * (sy ** 2 + sz ** 2) / 12,
                        iyy=mass * (sx ** 2 + sz ** 2) / 12, izz=mass * (sx ** 2 + sy ** 2) / 12)
    return Model(name, pose=pose, links=[Link('link', inertial=inertial, collisions=[
        Collision('c', Geometry('box', size=size), surface=surface or Surface())])])


def arm(name, joint_type='revolute', damping=0.0, y=0.0, z=2.0):
    link = Link('arm', pose=Pose((0.5, y, z)), inertial=Inertial(1.0, ixx=1e-3, iyy=1 / 12,
                                                                 izz=1 / 12),
                collisions=[Collision('c', Geometry('box', size=(1, 0.05, 0.05)))])
    j = Joint('j', joint_type, 'world', 'arm', anchor=np.array([0.0, y, z]),
              axis=np.array([0.0, 1, 0] if joint_type != 'prismatic' else [1.0, 0, 0]),
              lower=-1.0, upper=1.0, damping=damping, effort=50.0, velocity=3.0)
    return Model(name, links=[link], joints=[j])


def state(pw):
    rows = []
    for m in pw.models.values():
        for link in m.links.values():
            if link.body is not None:
                b = link.body
                rows.append(list(b.getPosition()) + list(b.getQuaternion())
                            + list(b.getLinearVel()) + list(b.getAngularVel()))
    return np.array(rows)


def run_both(build, script, steps, every=50):
    """Step the scene built by build(pw) under each core from the same ODE random seed (its
    quickStep reorders constraints randomly), calling script(pw, k) before step k; returns the
    largest difference of the body states sampled every `every` steps, and the worlds."""
    worlds, samples = {}, {}
    for core in ('python', 'compiled'):
        _core.set_random_seed(1)
        pw = PhysicsWorld(Physics(), core=core)
        build(pw)
        samples[core] = []
        for k in range(steps):
            script(pw, k)
            pw.step(1)
            if k % every == every - 1:
                samples[core].append(state(pw))
        assert pw.time == pytest.approx(steps * 0.001)
        worlds[core] = pw
    worst = 0.0
    for a, b in zip(samples['python'], samples['compiled']):
        assert a.shape == b.shape
        worst = max(worst, float(np.max(np.abs(a - b))))
    return worst, worlds


def test_the_compiled_core_is_built_and_reads_pyode_ids():
    check_layout()          # raises ModelError naming what is missing


def test_contacts_friction_bounce_and_fdir_match_the_python_loop():
    def build(pw):
        pw.add_model(ground())
        pw.add_model(box('slider', Pose((0, 0, 0.25)), surface=Surface(mu1=0.3, mu2=0.3)))
        pw.add_model(box('ball', Pose((2, 0, 1.0)), surface=Surface(bounce=0.6,
                                                                    bounce_threshold=0.01)))
        pw.add_model(box('aniso', Pose((-2, 0, 0.25)), surface=Surface(
            mu1=1.0, mu2=0.05, fdir1=(1.0, 0.0, 0.0))))
        pw.add_model(box('stack', Pose((0, 2, 0.25))))
        pw.add_model(box('stack2', Pose((0, 2, 0.7)), size=(0.3, 0.3, 0.3)))

    def push(pw, k):
        if k < 800:
            for name in ('slider', 'aniso'):
                pw.models[name].links['link'].add_force((6.0, 3.0, 0.0))

    worst, worlds = run_both(build, push, 3000)
    assert worst < TOL
    moved = worlds['compiled'].models['slider'].pose().p
    assert moved[0] > 0.5                   # it really slid


def test_joint_motor_servo_effort_and_damping_match_the_python_loop():
    def build(pw):
        pw.add_model(arm('servo'))
        pw.add_model(arm('motor', joint_type='continuous', y=1.0))
        pw.add_model(arm('effort', damping=0.5, y=2.0))
        pw.add_model(arm('rail', joint_type='prismatic', damping=0.2, y=3.0))

    def drive(pw, k):
        if k == 0:
            pw.models['servo'].joints['j'].set_position_target(0.7)
            pw.models['motor'].joints['j'].set_velocity(2.0, fmax=30.0)
            pw.models['effort'].joints['j'].set_effort(-8.0)
            pw.models['rail'].joints['j'].set_effort(3.0)
        if k == 1000:
            pw.models['servo'].joints['j'].set_position_target(-0.4)
            pw.models['effort'].joints['j'].release()

    worst, worlds = run_both(build, drive, 2000)
    assert worst < TOL
    pw = worlds['compiled']
    assert abs(pw.models['motor'].joints['j'].velocity()) > 0.5      # the motor turns
    e_py = worlds['python'].models['rail'].joints['j'].effort()
    assert pw.models['rail'].joints['j'].effort() == pytest.approx(e_py, abs=TOL)


def test_sleeping_models_wake_when_touched_as_in_the_python_loop():
    def build(pw):
        pw.add_model(ground())
        pw.add_model(box('sleeper', Pose((1.0, 0, 0.2))))
        pw.add_model(box('hammer', Pose((0, 0, 0.2)), mass=5.0))

    def push(pw, k):
        if 1500 <= k < 2500:
            pw.models['hammer'].links['link'].add_force((150.0, 0.0, 0.0))

    worst, worlds = run_both(build, push, 4000)
    assert worst < TOL
    assert worlds['compiled'].models['sleeper'].pose().p[0] > 1.05     # it was pushed


def test_space_scanner_in_the_office_matches_the_python_loop():
    world = sdf.load_world(os.path.join(SRC, 'sim', 'ode_sim', 'worlds', 'office.world'))
    rel = 'space_scanner/space_scanner_description/urdf/chassi_bot.urdf.xacro'
    exe = shutil.which('xacro')
    assert exe is not None, 'xacro is not on PATH: the workspace is not built or not sourced'
    out = subprocess.run([exe, os.path.join(SRC, rel)], capture_output=True, text=True,
                         timeout=60)
    assert out.returncode == 0, out.stderr
    worlds, samples = {}, {}
    for core in ('python', 'compiled'):
        _core.set_random_seed(1)
        pw = PhysicsWorld(world.physics, world.gravity, core=core)
        for m in world.models:
            pw.add_model(m)
        robot = urdf.parse_urdf(out.stdout, os.path.join(SRC, rel), 'robot')
        robot.pose = Pose((0.5, 0.3, 0.05))
        m = pw.add_model(robot)
        for j in m.joints.values():
            if j.hinge:
                j.set_velocity(3.0, fmax=5.0)
        samples[core] = []
        for _ in range(4):
            pw.step(500)
            samples[core].append(state(pw))
        worlds[core] = pw
    for a, b in zip(samples['python'], samples['compiled']):
        assert np.max(np.abs(a - b)) < TOL
    assert worlds['compiled'].models['robot'].pose().p[0] != pytest.approx(0.5, abs=0.05)


def test_broad_phase_keeps_every_contact_near_and_far_as_the_python_loop():
    """The broad phase skips disjoint model spaces and far static geoms, never a real contact:
    a box shoved into a second box pushes it (two awake models), a box dropped on a static
    block far from the origin lands on the block, not the floor, and a box beside a static wall
    it is pushed into stops at the wall - with the same trajectories in both loops."""
    def static_block(name, pose, size):
        return Model(name, static=True, pose=pose, links=[Link('link', collisions=[
            Collision('c', Geometry('box', size=size))])])

    def build(pw):
        pw.add_model(ground())
        pw.add_model(box('pusher', Pose((0.0, 0, 0.2))))
        pw.add_model(box('pushed', Pose((0.6, 0, 0.2))))
        pw.add_model(static_block('block', Pose((20.0, 20.0, 0.5)), (1.0, 1.0, 1.0)))
        pw.add_model(box('dropped', Pose((20.0, 20.0, 1.5))))
        pw.add_model(static_block('wall', Pose((-20.0, 1.0, 0.5)), (4.0, 0.2, 1.0)))
        pw.add_model(box('walled', Pose((-20.0, 0.0, 0.2))))

    def push(pw, k):
        if k < 2000:
            pw.models['pusher'].links['link'].add_force((40.0, 0.0, 0.0))
            pw.models['walled'].links['link'].add_force((0.0, 40.0, 0.0))

    worst, worlds = run_both(build, push, 3000)
    assert worst < TOL
    pw = worlds['compiled']
    assert pw.models['pushed'].pose().p[0] > 0.7                       # it was pushed
    assert pw.models['dropped'].pose().p[2] == pytest.approx(1.2, abs=0.01)   # on the block
    walled = pw.models['walled'].pose().p[1]
    assert 0.65 < walled < 0.71                     # against the wall (its face at y = 0.9)
