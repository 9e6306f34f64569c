"""The window's editing tools against the real simulator under Xvfb: editor_scenario.py
(pytest-qt) in a process of its own on this test's display and roscore, on ode_sim's empty
world. See editor_scenario.py for the steps."""
import os
import subprocess
import sys

from course_testing import Proc
from course_testing.gui_check import keep

HERE = os.path.dirname(os.path.abspath(__file__))


def test_editing_tools(roscore, screen, tmp_path):
    env = dict(roscore.env, DISPLAY=screen.display, SCENARIO_OUT=str(tmp_path))
    env.pop('QT_QPA_PLATFORM', None)
    sim = Proc(['rosrun', 'ode_sim', 'sim_node', 'worlds/empty.world'], env=env,
               log=str(tmp_path / 'sim.log'))
    try:
        run = subprocess.run([sys.executable, '-m', 'pytest', '-q', '-x', '-p', 'no:cacheprovider',
                              '-o', 'qt_api=pyqt5', os.path.join(HERE, 'editor_scenario.py')],
                             env=env, capture_output=True, text=True, timeout=800, cwd=HERE)
        (tmp_path / 'scenario.log').write_text(run.stdout + run.stderr)
        if (tmp_path / 'walls.png').exists():
            keep(str(tmp_path / 'walls.png'), 'ode_sim_gui_editor_walls.png')
        assert run.returncode == 0, 'scenario failed (log %s):\n%s' % (
            tmp_path / 'scenario.log', run.stdout[-6000:] + run.stderr[-3000:])
        assert sim.alive(), sim.output()[-2000:]
    finally:
        sim.stop()
