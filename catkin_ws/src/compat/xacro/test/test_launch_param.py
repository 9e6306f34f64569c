"""roslaunch loads robot_description through both `command=` forms (private roscore)."""
import os
import subprocess
import xml.etree.ElementTree as ET

from course_testing import Proc, wait_for

HERE = os.path.dirname(os.path.abspath(__file__))


def _get(env, name):
    r = subprocess.run(['rosparam', 'get', name], capture_output=True, text=True, env=env,
                       timeout=120)
    return r.stdout if r.returncode == 0 else None


def test_both_command_forms(roscore, tmp_path):
    launch = Proc(['roslaunch', os.path.join(HERE, 'fixtures', 'description.launch')],
                  env=roscore.env, log=str(tmp_path / 'roslaunch.log'))
    try:
        by_find = wait_for(lambda: _get(roscore.env, '/robot_description'), 30, 0.3,
                           '/robot_description')
        on_path = wait_for(lambda: _get(roscore.env, '/robot_description_path'), 30, 0.3,
                           '/robot_description_path')
    finally:
        launch.stop()
    # rosparam prints YAML; the URDF is a block scalar: load it back as YAML
    import yaml
    for text, first, last in ((by_find, 'by_find_footprint', 'laser'),
                              (on_path, 'fixture_bot_footprint', 'no_laser')):
        robot = ET.fromstring(yaml.safe_load(text))
        names = [l.get('name') for l in robot.findall('link')]
        assert names[0] == first and names[-1] == last, names


def test_bad_model_fails_the_launch(roscore, tmp_path):
    """A broken xacro makes roslaunch fail with xacro's one-line message in its output."""
    log = str(tmp_path / 'roslaunch.log')
    bad = os.path.join(HERE, 'fixtures', 'bad_undefined_property.xacro')
    launch = Proc(['roslaunch', os.path.join(HERE, 'fixtures', 'description.launch'),
                   'model:=' + bad], env=roscore.env, log=log)
    try:
        rc = launch.popen.wait(60)
    finally:
        launch.stop()
    assert rc != 0
    assert "undefined property or name 'lenght'" in launch.output()
