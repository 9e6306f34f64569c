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
