"""The ros_control bridge (libgazebo_ros_control.so): commands, PID, limits, e-stop, lockstep.

Unit tests call the plugin directly (no roscore). The last test drives the contract over real
topics: this file, run as a script under a private roscore, is a RobotHW-like client holding a
pendulum at 0.5 rad while the physics and the plugin step in lockstep in a thread.
"""
import os
import sys
import threading
import time

import numpy as np
import pytest
import rospy

from sensor_msgs.msg import JointState
from std_msgs.msg import Bool
from ode_sim.ros import plugins
from ode_sim.description.model import (Collision, Geometry, Inertial, Joint, Link, Model, ModelError, Physics,
                                       Plugin as PluginDesc, Transmission)
from ode_sim.engine.physics import PhysicsWorld
from ode_sim.ros.plugins.base import PluginContext
from ode_sim.ros.plugins.rosio import FakeClock, RosIO
from ode_sim.description.transforms import Pose

I_ARM = 1 / 12 + 0.25           # 1 kg, 1 m arm about its end
I_SPIN = 0.1


def rig(interfaces, arm_lower=-1.5, arm_upper=1.5):
    """'hinge': a 1 kg, 1 m arm on a revolute joint about Y at 2 m (gravity pulls it down);
    'spin': a disc on a continuous joint about Z (no gravity torque), both fixed to the world."""
    arm = Link('arm', pose=Pose((0.5, 0, 2)),
               inertial=Inertial(1.0, ixx=1e-3, iyy=1 / 12, izz=1 / 12),
               collisions=[Collision('c', Geometry('box', size=(1, 0.05, 0.05)))])
    disc = Link('disc', pose=Pose((3, 0, 1)),
                inertial=Inertial(2.0, ixx=0.05, iyy=0.05, izz=I_SPIN))
    joints = [Joint('hinge', 'revolute', 'world', 'arm', anchor=np.array([0.0, 0, 2]),
                    axis=np.array([0.0, 1, 0]), lower=arm_lower, upper=arm_upper, effort=50.0,
                    velocity=5.0),
              Joint('spin', 'continuous', 'world', 'disc', anchor=np.array([3.0, 0, 1]),
                    axis=np.array([0.0, 0, 1]), effort=2.0, velocity=3.0)]
    trans = [Transmission('t_' + j, 'transmission_interface/SimpleTransmission',
                          joints={j: [iface]}, actuators={'m_' + j: 2.0})
             for j, iface in interfaces.items()]
    return Model('rig', links=[arm, disc], joints=joints, transmissions=trans)


class FakeSub:
    def __init__(self, connections=1):
        self.connections = connections

    def get_num_connections(self):
        return self.connections

    def unregister(self):
        pass


class LeavingSub(FakeSub):
    """A command subscriber whose publisher leaves after `reads` connection checks: the
    moment is fixed by the plugin's own checks, not by a timer on the wall clock."""

    def __init__(self, reads):
        super().__init__(1)
        self.reads = reads

    def get_num_connections(self):
        self.reads -= 1
        return 1 if self.reads >= 0 else 0


def bridge(interfaces, lockstep=False, wall=None, io=None, **params):
    pw = PhysicsWorld(Physics())
    m = pw.add_model(rig(interfaces))
    ctx = PluginContext(pw, None, lockstep=lockstep, wall=wall, io=io)
    cls = plugins.lookup('libgazebo_ros_control.so')
    plug = cls(ctx, m, PluginDesc('gazebo_ros_control', 'libgazebo_ros_control.so',
                                  {k: str(v) for k, v in params.items()}))
    return pw, m, plug


def command(plug, stamp=None, **values):
    """A joint_commands message: name=(array, value) pairs, e.g. hinge=('position', 0.5)."""
    msg = JointState()
    if stamp is not None:
        msg.header.stamp = stamp
    for name, (array, value) in values.items():
        msg.name.append(name)
        for a in ('position', 'velocity', 'effort'):
            getattr(msg, a).append(value if a == array else float('nan'))
    plug.on_command(msg)


def run(pw, plug, seconds):
    for _ in range(int(round(seconds / pw.dt))):
        plug.before_step()
        pw.step()
        plug.update()


def test_contract_state_topic_and_joint_descriptions():
    pw, m, plug = bridge({'hinge': 'hardware_interface/PositionJointInterface',
                         'spin': 'VelocityJointInterface'}, controlPeriod=0.01)
    assert plug.ns == 'rig' and plug.state_topic == '/rig/ode_sim/joint_states'
    assert plug.command_topic == '/rig/ode_sim/joint_commands'
    assert plug.control_period == pytest.approx(0.01)
    assert [j.description() for j in plug.joints] == [
        {'name': 'hinge', 'interface': 'PositionJointInterface', 'reduction': 2.0,
         'lower': -1.5, 'upper': 1.5, 'effort': 50.0, 'velocity': 5.0},
        {'name': 'spin', 'interface': 'VelocityJointInterface', 'reduction': 2.0,
         'effort': 2.0, 'velocity': 3.0}]
    run(pw, plug, 0.1)
    sent = plug.state_pub.sent
    assert len(sent) == 10                                  # once per control period
    stamps = [s.header.stamp.to_sec() for s in sent]
    np.testing.assert_allclose(np.diff(stamps), 0.01, atol=1e-9)
    assert stamps[0] == 0.0
    assert sent[-1].name == ['hinge', 'spin'] and len(sent[-1].effort) == 2
    # no command yet: the position joint holds where it was, the velocity joint stands
    assert m.joints['hinge'].position() == pytest.approx(0.0, abs=0.01)


def test_position_hold_with_pid_and_with_the_motor():
    pw, m, plug = bridge({'hinge': 'PositionJointInterface'})
    plug.set_pid_gains('hinge', p=200.0, i=1000.0, d=20.0, i_clamp=20.0)
    command(plug, hinge=('position', 0.5))
    run(pw, plug, 4.0)
    assert m.joints['hinge'].position() == pytest.approx(0.5, abs=0.005)
    assert abs(m.joints['hinge'].velocity()) < 0.01
    pw, m, plug = bridge({'hinge': 'PositionJointInterface'})
    command(plug, hinge=('position', 0.5))
    run(pw, plug, 1.0)
    assert m.joints['hinge'].position() == pytest.approx(0.5, abs=0.005)


def test_velocity_tracking_with_the_motor_and_with_pid():
    pw, m, plug = bridge({'spin': 'VelocityJointInterface'})
    command(plug, spin=('velocity', 2.0))
    run(pw, plug, 1.0)
    assert m.joints['spin'].velocity() == pytest.approx(2.0, rel=0.02)
    assert m.joints['spin'].vel_cmd == (2.0, 2.0)            # fmax = the effort limit
    run(pw, plug, 3.0)                                      # past +-pi: the state unwraps
    # 4 s at 2 rad/s less 0.1 rad lost accelerating at 2 N m / 0.1 kg m^2
    assert plug.state_pub.sent[-1].position[0] == pytest.approx(8.0 - 0.1, abs=0.02)
    pw, m, plug = bridge({'spin': 'VelocityJointInterface'})
    plug.set_pid_gains('spin', p=1.0, i=2.0, i_clamp=1.0)
    command(plug, spin=('velocity', 2.0))
    run(pw, plug, 3.0)
    assert m.joints['spin'].velocity() == pytest.approx(2.0, rel=0.02)


def test_effort_accelerates_a_free_joint_as_tau_over_inertia():
    pw, m, plug = bridge({'spin': 'EffortJointInterface'})
    command(plug, spin=('effort', 0.5))
    run(pw, plug, 1.0)
    assert m.joints['spin'].velocity() == pytest.approx(0.5 / I_SPIN * 1.0, rel=0.01)


def test_limits_clamp_position_velocity_and_effort_commands():
    pw, m, plug = bridge({'hinge': 'PositionJointInterface', 'spin': 'EffortJointInterface'})
    command(plug, hinge=('position', 3.0), spin=('effort', 10.0))
    run(pw, plug, 1.0)
    assert m.joints['hinge'].position() == pytest.approx(1.5, abs=0.01)   # upper limit
    # effort limit 2 N m: a = 2 / I, but the velocity grows no faster than that
    assert m.joints['spin'].velocity() == pytest.approx(2.0 / I_SPIN, rel=0.01)
    pw, m, plug = bridge({'spin': 'VelocityJointInterface'})
    command(plug, spin=('velocity', 10.0))
    run(pw, plug, 1.0)
    assert m.joints['spin'].velocity() == pytest.approx(3.0, rel=0.01)     # velocity limit


def test_nan_and_missing_names_keep_the_previous_command(monkeypatch):
    warnings = []
    monkeypatch.setattr(rospy, 'logwarn', lambda m, *a: warnings.append(m % a if a else m))
    pw, m, plug = bridge({'hinge': 'PositionJointInterface', 'spin': 'VelocityJointInterface'})
    command(plug, hinge=('position', 0.3), spin=('velocity', 1.0))
    command(plug, hinge=('position', float('nan')))
    command(plug, spin=('position', 7.0))          # wrong array for a velocity joint: no change
    command(plug, bogus=('effort', 1.0))
    command(plug, bogus=('effort', 1.0))
    assert plug.by_name['hinge'].command == 0.3 and plug.by_name['spin'].command == 1.0
    assert sum("'bogus' takes no commands" in w for w in warnings) == 1


def test_estop_zeroes_and_holds():
    pw, m, plug = bridge({'hinge': 'PositionJointInterface', 'spin': 'VelocityJointInterface'},
                         eStopTopic='e_stop')
    command(plug, hinge=('position', 0.8), spin=('velocity', 2.0))
    run(pw, plug, 0.3)
    plug.on_estop(Bool(True))
    held = m.joints['hinge'].position()
    run(pw, plug, 0.5)
    assert plug.by_name['hinge'].hold == pytest.approx(held)
    assert m.joints['spin'].velocity() == pytest.approx(0.0, abs=0.01)
    assert m.joints['hinge'].position() == pytest.approx(held, abs=0.01)
    plug.on_estop(Bool(False))
    run(pw, plug, 1.0)
    assert m.joints['spin'].velocity() == pytest.approx(2.0, rel=0.02)
    assert m.joints['hinge'].position() == pytest.approx(0.8, abs=0.01)


def test_control_period_messages_sim_type_and_bad_transmissions(monkeypatch):
    logs = []
    for level in ('logwarn', 'logerr'):
        monkeypatch.setattr(rospy, level, lambda m, *a, level=level: logs.append((level, m)))
    bridge({'hinge': 'PositionJointInterface'}, controlPeriod=0.0005)
    assert ('logerr', 'Desired controller update period (0.0005 s) is faster than the gazebo '
            'simulation period (0.001 s).') in logs
    _, _, plug = bridge({'hinge': 'PositionJointInterface'}, controlPeriod=0.02,
                        robotSimType='my_pkg/MyRobotHWSim')
    assert plug.control_period == 0.02
    assert any(lv == 'logwarn' and 'is slower than the gazebo' in m for lv, m in logs)
    assert any('robotSimType' in m for _, m in logs)
    with pytest.raises(ModelError, match="No matching hardware interface found for 'Torque"):
        bridge({'hinge': 'TorqueInterface'})
    pw = PhysicsWorld(Physics())
    model = rig({})
    model.transmissions = [Transmission('t', 'x', joints={'elbow': [POS]}, actuators={'m': 1})]
    with pytest.raises(ModelError, match='joint named "elbow" which is not in the gazebo model'):
        plugins.lookup('libgazebo_ros_control.so')(
            PluginContext(pw, None), pw.add_model(model),
            PluginDesc('c', 'libgazebo_ros_control.so', {}))


POS = 'PositionJointInterface'


def test_lockstep_waits_for_the_command_of_the_period():
    pw, m, plug = bridge({'hinge': POS}, lockstep=True, controlPeriod=0.01)
    plug.cmd_sub = FakeSub(1)
    plug.lockstep_timeout = 5.0
    answered = []                   # a client answering each new state 50 ms after it came

    def client():
        deadline = time.monotonic() + 60                # a hang guard, not a measure
        for _ in range(3):
            # the next state (the simulator waits for its command), whenever it comes
            while len(plug.state_pub.sent) <= len(answered):
                assert time.monotonic() < deadline, 'no state %d' % len(answered)
                time.sleep(0.001)
            time.sleep(0.05)
            stamp = plug.state_pub.sent[-1].header.stamp
            answered.append(stamp.to_sec())
            command(plug, stamp=stamp, hinge=('position', 0.1 * len(answered)))
    t = threading.Thread(target=client)
    t.start()
    for _ in range(30):
        plug.before_step()
        pw.step()
    t.join()
    assert plug.waits == 3 and plug.synced == 3 and plug.timeouts == 0
    assert plug.by_name['hinge'].command == pytest.approx(0.3)
    assert answered[:3] == pytest.approx([0.0, 0.01, 0.02])


def test_lockstep_times_out_with_one_warning_and_resumes(monkeypatch):
    warnings = []
    monkeypatch.setattr(rospy, 'logwarn', lambda m, *a: warnings.append(m % a if a else m))
    wall = FakeClock()                              # the timeouts cost no wall time
    pw, m, plug = bridge({'hinge': POS}, lockstep=True, wall=wall, controlPeriod=0.01)
    plug.lockstep_timeout = 30.0
    plug.cmd_sub = FakeSub(0)                       # nobody publishes commands: no waiting
    run(pw, plug, 0.05)
    assert plug.waits == 0 and plug.timeouts == 0
    plug.cmd_sub.connections = 1
    run(pw, plug, 0.05)                             # one timeout, then steps on
    assert plug.waits == 1 and plug.timeouts == 1
    assert [w for w in warnings if 'lockstep' in w] == [
        'ode_sim: lockstep: no joint command for t=0.050 from /rig/ode_sim/joint_commands '
        'within 30.0 s; stepping on with the last command']
    assert wall.now() >= 30.0
    command(plug, stamp=plug.state_pub.sent[-1].header.stamp, hinge=('position', 0.2))
    run(pw, plug, 0.01)                             # commands flowed: waits (and times out) again
    assert plug.waits == 2 and plug.timeouts == 2


def test_lockstep_stops_waiting_when_the_controller_leaves(monkeypatch):
    """A controller node that exits (or unregisters its publisher) while the simulator waits
    for its command: the wait ends without the timeout warning, and no later boundary waits."""
    warnings = []
    monkeypatch.setattr(rospy, 'logwarn', lambda m, *a: warnings.append(m % a if a else m))
    pw, m, plug = bridge({'hinge': POS}, lockstep=True, controlPeriod=0.01)
    plug.lockstep_timeout = 600.0                   # a test that hung here would say so
    plug.cmd_sub = LeavingSub(2)                    # there when the wait starts, then gone
    run(pw, plug, 0.05)
    assert plug.waits == 1 and plug.timeouts == 0 and plug.synced == 0
    assert not [w for w in warnings if 'lockstep' in w]


# ---------------------------------------------------------------------- over real topics
def test_contract_over_real_topics_in_lockstep(roscore, tmp_path):
    from course_testing import run as run_proc
    log = str(tmp_path / 'bridge.log')
    rc, timed_out = run_proc([sys.executable, os.path.abspath(__file__), '--integration'], 60,
                             env=roscore.env, log=log)
    out = open(log).read()
    assert not timed_out and rc == 0, out[-3000:]
    assert 'OK hold' in out, out[-3000:]


def test_controller_node_started_and_stopped(monkeypatch, tmp_path):
    """With ROS up and controllerNode=true the plugin starts gazebo_ros_control_node in NS (here
    a stand-in script that records its arguments) and stops it on shutdown; controllerNode=false
    starts none."""
    from ode_sim.ros.plugins import control
    import roslib.packages
    args = tmp_path / 'args'
    fake = tmp_path / 'gazebo_ros_control_node'
    fake.write_text('#!/bin/sh\necho "$@" > %s\nexec sleep 60\n' % args)
    fake.chmod(0o755)

    class LiveIO:                   # "ROS is up", endpoints that do nothing
        live = True

        def publisher(self, *a, **k):
            return None

        def subscriber(self, *a, **k):
            return None

    monkeypatch.setattr(control.GazeboRosControl, '_load_ros_params', lambda self: None)
    monkeypatch.setattr(roslib.packages, 'find_node', lambda pkg, node: [str(fake)])
    _, _, plug = bridge({'hinge': POS}, io=LiveIO(), eStopTopic='estop', controllerNode='true')
    proc = plug.node_proc
    assert proc is not None and proc.poll() is None
    deadline = time.monotonic() + 10
    while not args.exists() or not args.read_text().strip():
        assert time.monotonic() < deadline, 'the node was not started'
        time.sleep(0.02)
    assert args.read_text().split() == ['__ns:=/rig', '__name:=gazebo_ros_control', '--parent-pid',
                                        str(os.getpid()), '--estop-topic', 'estop']
    plug.shutdown()
    assert proc.poll() is not None and plug.node_proc is None
    _, _, plug = bridge({'hinge': POS}, io=LiveIO(), controllerNode='false')
    assert plug.node_proc is None
    monkeypatch.setattr(roslib.packages, 'find_node', lambda pkg, node: [])
    _, _, plug = bridge({'hinge': POS}, io=LiveIO(), controllerNode='true')
    assert plug.node_proc is None       # not built: an ERROR, the bridge still loads
    with pytest.raises(ModelError, match='controllerNode'):
        bridge({'hinge': POS}, io=LiveIO(), controllerNode='maybe')


def integration():
    """A client like the coming RobotHW: reads NS/ode_sim/joint_states, answers each state with
    a position command on NS/ode_sim/joint_commands (same stamp). The sim runs here too."""
    rospy.init_node('control_bridge_check')
    pw, m, plug = bridge({'hinge': POS}, lockstep=True, io=RosIO(), controlPeriod=0.005,
                         controllerNode='false')      # this script is the controller side
    joints = rospy.get_param('/rig/ode_sim/joints')
    assert joints[0]['name'] == 'hinge' and joints[0]['interface'] == POS, joints
    assert rospy.get_param('/rig/ode_sim/control_period') == 0.005
    cmd_pub = rospy.Publisher('/rig/ode_sim/joint_commands', JointState, queue_size=10)
    states = []

    def on_state(msg):
        states.append(msg)
        out = JointState()
        out.header.stamp = msg.header.stamp
        out.name = ['hinge']
        out.position = [0.5]
        cmd_pub.publish(out)
    rospy.Subscriber('/rig/ode_sim/joint_states', JointState, on_state, queue_size=10)
    deadline = time.monotonic() + 10
    while plug.cmd_sub.get_num_connections() == 0 or cmd_pub.get_num_connections() == 0:
        assert time.monotonic() < deadline, 'the client never connected'
        time.sleep(0.05)
    done = threading.Event()

    def sim():
        run(pw, plug, 1.0)
        done.set()
    threading.Thread(target=sim, daemon=True).start()
    assert done.wait(40), 'the simulation did not finish 1 s of sim time'
    q = m.joints['hinge'].position()
    stamps = [s.header.stamp.to_sec() for s in states]
    print('states %d synced %d waits %d timeouts %d hinge %.4f'
          % (len(states), plug.synced, plug.waits, plug.timeouts, q))
    assert plug.timeouts == 0, 'lockstep timed out'
    assert plug.synced == 200, plug.synced        # every period stepped with its own command
    assert len(states) == 200 and np.allclose(np.diff(stamps), 0.005), stamps[:5]
    assert abs(q - 0.5) < 0.005, q
    print('OK hold')


if __name__ == '__main__' and '--integration' in sys.argv:
    try:
        integration()
        code = 0
    except AssertionError as e:
        print('FAILED: %s' % e)
        code = 1
    sys.stdout.flush()
    os._exit(code)      # skip interpreter teardown (PyODE objects, rospy threads)
