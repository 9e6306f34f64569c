"""Topic Monitor and Console docked in rqt_gui (Xvfb + private roscore + talker)."""
import os
import sys

import pytest
from course_testing import Proc, wait_for
from course_testing.rqt_driver import gui_env, states

HERE = os.path.dirname(os.path.abspath(__file__))


@pytest.mark.full
def test_topic_monitor_and_console(roscore, xvfb, tmp_path):
    env = gui_env(roscore.env, xvfb.display, tmp_path / 'config')
    procs = []
    try:
        procs.append(Proc(['rosrun', 'rospy_tutorials', 'talker'], env=env, log=str(tmp_path / 'talker.log')))
        gui = Proc([sys.executable, os.path.join(HERE, 'check_monitor_driver.py')], env=env,
                   log=str(tmp_path / 'gui.log'))
        procs.append(gui)
        wait_for(lambda: not gui.alive(), 120, 0.3, 'the scripted rqt_gui to finish')
        got = {s.get('kind', 'error'): s for s in states(gui.output())}
        assert gui.popen.returncode == 0 and 'excluded' in got, gui.output()[-3000:]
    finally:
        for p in reversed(procs):
            p.stop()
    m = got['monitor']
    topic, type_name, bw, hz, _ = m['row']
    assert (topic, type_name) == ('/chatter', 'std_msgs/String')
    assert 8.0 < float(hz) < 12.0, hz                     # the talker publishes at 10 Hz
    assert bw.endswith('B/s') and float(bw[:-3].rstrip('K')) > 0
    assert m['children'][0][0] == '/data' and m['children'][0][1].startswith("'hello world")
    assert m['fake'] == 'can not get message class for type "no_pkg/NoType"'
    assert all(r[0].startswith('hello world') and r[1] == 2 for r in m['console'])
    assert m['status'].startswith('Displaying ')
    assert got['excluded']['talker_rows'] == 0
    assert ' of ' in got['excluded']['status']
