"""rqt_controller_manager on the dummy robot (Xvfb + private roscore): the controller manager is
found, configured controllers are listed as uninitialized, and the context menu's actions load,
start, stop and unload a controller — checked against list_controllers."""
import os
import subprocess
import sys

from course_testing import Proc, wait_for
from course_testing.rqt_driver import gui_env, states

HERE = os.path.dirname(os.path.abspath(__file__))


def test_controller_manager_plugin_drives_the_dummy_robot(roscore, xvfb, tmp_path):
    env = gui_env(roscore.env, xvfb.display, tmp_path / 'config')
    procs = []
    try:
        subprocess.run(['rosparam', 'load', subprocess.run(
            ['rospack', 'find', 'controller_manager_tests'], env=env, capture_output=True, text=True,
            check=True).stdout.strip() + '/config/test_controllers.yaml'], env=env, check=True, timeout=60)
        procs.append(Proc(['rosrun', 'controller_manager_tests', 'dummy_robot_hw'], env=env,
                          log=str(tmp_path / 'robot.log')))
        gui = Proc([sys.executable, os.path.join(HERE, 'check_cm_driver.py')], env=env, log=str(tmp_path / 'gui.log'))
        procs.append(gui)
        wait_for(lambda: not gui.alive(), 120, 0.2, 'rqt_controller_manager scenario to finish')
        got = states(gui.output())
        listed = subprocess.run(['rosrun', 'controller_manager', 'controller_manager', 'list'], env=env,
                                capture_output=True, text=True, timeout=60).stdout
    finally:
        for p in reversed(procs):
            p.stop()
    assert gui.popen.returncode == 0 and not [s for s in got if 'error' in s], gui.output()[-3000:]
    first = got[0]
    assert first['cm'] == '/controller_manager'
    assert first['rows']['velocity_j2'] == 'uninitialized' and first['rows']['effort_j1'] == 'uninitialized'
    menus = [s for s in got if s['kind'] == 'menu']
    assert menus[0]['labels'] == ['Load', 'Load and Start']
    assert menus[1]['labels'] == ['Stop', 'Stop and Unload']
    assert menus[2]['labels'] == ['Start again', 'Unload']
    after = [s['rows']['velocity_j2'] for s in got if s['kind'] == 'after']
    assert after == ['running', 'stopped', 'running', 'uninitialized']
    assert 'velocity_j2' not in listed
