"""Practical 5 with rqt instead of `rostopic pub`: the Message Publisher commands the wheel's
effort_controllers/JointPositionController of my_robot_simulation_control's robot in the
simulator (headless, lockstep) and the joint reaches the commanded 1.5 rad on /diffrobot/joint_states."""
import os
import sys

from course_testing import Proc, wait_for
from course_testing.sim_testing import probe
from course_testing.rqt_driver import gui_env, states

HERE = os.path.dirname(os.path.abspath(__file__))
COMMAND = '/diffrobot/joint1_position_controller/command'


def test_message_publisher_commands_position_controller(roscore, xvfb, tmp_path):
    env = gui_env(roscore.env, xvfb.display, tmp_path / 'config')
    stop = tmp_path / 'stop'
    sim_log = tmp_path / 'sim.log'
    procs = []
    latest = {}

    def joints():
        js = probe(['topic', '/diffrobot/joint_states', '--timeout', '120'], env, timeout=150.0,
                   proc=procs[0])
        latest.update(js)
        return js

    try:
        procs.append(Proc(['roslaunch', 'my_robot_simulation_control', 'robot_sim_control.launch',
                           'gui:=false'], env=env, log=str(sim_log)))
        before = joints()
        assert abs(before['position']['wheel_left_joint']) < 0.2, 'the wheel was not at rest: %r' % before
        gui = Proc([sys.executable, os.path.join(HERE, 'check_publisher_controller_driver.py'),
                    COMMAND, str(stop)], env=env, log=str(tmp_path / 'publisher.log'))
        procs.append(gui)
        wait_for(lambda: abs(joints()['position']['wheel_left_joint'] - 1.5) < 0.05 or not gui.alive(),
                 240, 0.5, 'the left wheel to reach 1.5 rad (last joint states %r; see %s)'
                 % (latest, tmp_path / 'publisher.log'))
        reached = dict(latest)
        stop.write_text('stop')
        wait_for(lambda: not gui.alive(), 60, 0.2, 'rqt_publisher to finish')
        got = {s.get('kind'): s for s in states(gui.output())}
        assert gui.popen.returncode == 0 and 'done' in got, gui.output()[-3000:]
    finally:
        for p in reversed(procs):
            p.stop()
    assert abs(reached['position']['wheel_left_joint'] - 1.5) < 0.05, reached
    assert abs(reached['position']['wheel_right_joint'] - before['position']['wheel_right_joint']) < 0.05, \
        'only joint 1 was commanded: %r' % reached
    assert reached['stamp'] > before['stamp']
    assert got['done']['counter'] >= 1
