"""Dynamic Reconfigure against a TestConfig server (Xvfb + private roscore)."""
import os
import sys

import pytest
from course_testing import Proc, wait_for
from course_testing.rqt_driver import gui_env, states

HERE = os.path.dirname(os.path.abspath(__file__))


@pytest.mark.full
def test_reconfigure_sets_parameters(roscore, xvfb, tmp_path):
    env = gui_env(roscore.env, xvfb.display, tmp_path / 'config')
    procs = []
    try:
        procs.append(Proc([sys.executable, os.path.join(HERE, 'reconfigure_server.py')], env=env,
                          log=str(tmp_path / 'server.log')))
        gui = Proc([sys.executable, os.path.join(HERE, 'check_reconfigure_driver.py')], env=env,
                   log=str(tmp_path / 'gui.log'))
        procs.append(gui)
        wait_for(lambda: not gui.alive(), 120, 0.3, 'the scripted rqt_reconfigure to finish')
        got = {s.get('kind', 'error'): s for s in states(gui.output())}
        assert gui.popen.returncode == 0 and 'config' in got, gui.output()[-3000:]
    finally:
        for p in reversed(procs):
            p.stop()
    assert '/reconf_test' in got['editors']['servers']
    assert {'int_', 'bool_', 'str_', 'int_enum_', 'deep_var_double'} <= set(got['editors']['names'])
    assert got['editors']['status'] == 'ERROR: value 99 of "double_" is out of range [-2.0, 10.0]'
    assert got['config'] == {'kind': 'config', 'int_': 7, 'bool_': True, 'double_': 0.0}


def test_reconfigure_changes_the_simulators_step_and_gravity(roscore, xvfb, tmp_path):
    """rqt_reconfigure on ode_sim's /gazebo (Gazebo's physics reconfigure): the step size and
    gravity typed into the editors are what get_physics_properties answers next."""
    env = gui_env(roscore.env, xvfb.display, tmp_path / 'config')
    procs = []
    try:
        procs.append(Proc(['roslaunch', 'gazebo_ros', 'empty_world.launch', 'gui:=false'],
                          env=env, log=str(tmp_path / 'sim.log')))
        gui = Proc([sys.executable, os.path.join(HERE, 'check_reconfigure_gazebo_driver.py')],
                   env=env, log=str(tmp_path / 'gui.log'))
        procs.append(gui)
        wait_for(lambda: not gui.alive(), 240, 0.3, 'the scripted rqt_reconfigure to finish')
        got = {s.get('kind', 'error'): s for s in states(gui.output())}
        assert gui.popen.returncode == 0 and 'physics' in got, \
            gui.output()[-3000:] + procs[0].output()[-2000:]
    finally:
        for p in reversed(procs):
            p.stop()
    assert {'time_step', 'max_update_rate', 'gravity_z', 'sor_pgs_iters'} <= set(got['editors']['names'])
    assert got['editors']['before'] == [0.001, -9.8]
    assert (got['physics']['time_step'], got['physics']['gravity_z']) == (0.002, -3.0)
    assert (got['physics']['config_time_step'], got['physics']['config_gravity_z']) == (0.002, -3.0)
