"""joint_state_publisher_gui starts under Xvfb and publishes the model's movable joints."""
import os
import subprocess

if not os.environ.get('DISPLAY'):       # the in-process test's Qt: offscreen when headless
    os.environ.setdefault('QT_QPA_PLATFORM', 'offscreen')

from course_testing import Proc, wait_for

URDF = '''<robot name="arm">
  <link name="base"/><link name="upper"/><link name="wheel"/>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <axis xyz="0 0 1"/><limit lower="-1.5" upper="1.5" effort="1" velocity="1"/></joint>
  <joint name="spin" type="continuous"><parent link="base"/><child link="wheel"/><axis xyz="0 1 0"/></joint>
</robot>'''


def test_gui_publishes_joint_states(roscore, xvfb, tmp_path):
    env = dict(roscore.env, DISPLAY=xvfb.display)
    env.pop('QT_QPA_PLATFORM', None)
    subprocess.run(['rosparam', 'set', '/robot_description', URDF], env=env, check=True, timeout=30)
    with Proc(['rosrun', 'joint_state_publisher_gui', 'joint_state_publisher_gui'], env=env,
              log=str(tmp_path / 'jsp.log')) as gui:
        r = subprocess.run(['rostopic', 'echo', '-n', '1', '/joint_states/name'], env=env,
                           capture_output=True, text=True, timeout=60)
        assert r.returncode == 0, gui.output()[-2000:]
        assert 'shoulder' in r.stdout and 'spin' in r.stdout, r.stdout
        wait_for(lambda: gui.alive(), 1)
        out = gui.output()
        assert 'TypeError' not in out and 'Traceback' not in out, out[-2000:]


def test_patch_rounds_floats(qapp):
    """In-process Qt on pytest-qt's application, which lives as long as the test process: a
    QApplication made here and dropped at the end would leave this slider, and every later
    in-process Qt test of the same pytest worker, without their application."""
    from python_qt_binding.QtWidgets import QSlider
    from jsp_gui_compat import patch_qt
    patch_qt()
    patch_qt()   # idempotent
    s = QSlider()
    s.setRange(0, 10000.0)
    s.setValue(10000 / 2)
    assert s.value() == 5000 and s.maximum() == 10000
