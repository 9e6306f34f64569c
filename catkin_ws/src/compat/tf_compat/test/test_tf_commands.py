"""The textbook's tf commands as written: `rosrun tf view_frames` against a running
robot_state_publisher writes frames.pdf and frames.gv in the current directory, Debian's other
tf executables stay reachable as `rosrun tf ...` / roslaunch pkg="tf", `import tf` works, and
`rosrun tf2_tools view_frames.py` still works. One roscore, one robot_state_publisher."""
import subprocess

import pytest

from course_testing import Proc, wait_for

URDF = """<robot name="probe">
  <link name="base_link"/> <link name="laser"/> <link name="imu_link"/>
  <joint name="laser_joint" type="fixed"><parent link="base_link"/><child link="laser"/>
    <origin xyz="0.1 0 0.2"/></joint>
  <joint name="imu_joint" type="fixed"><parent link="base_link"/><child link="imu_link"/></joint>
</robot>"""


def _run(cmd, env, cwd, timeout):
    try:
        return subprocess.run(cmd, env=env, cwd=cwd, capture_output=True, text=True,
                              timeout=timeout, stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired as e:
        pytest.fail('%s did not finish in %d s:\n%s' % (' '.join(cmd), timeout, e.stdout))


@pytest.fixture
def robot(roscore, tmp_path):
    env = roscore.env
    subprocess.run(['rosparam', 'set', 'robot_description', URDF], env=env, check=True,
                   timeout=30)
    rsp = Proc(['rosrun', 'robot_state_publisher', 'robot_state_publisher'], env=env,
               log=str(tmp_path / 'rsp.log'))
    try:
        wait_for(lambda: '/tf_static' in _run(['rostopic', 'list'], env, None, 30).stdout,
                 30, 0.5, 'robot_state_publisher to advertise /tf_static')
        yield env
    finally:
        rsp.stop()


def test_tf_commands(robot, tmp_path):
    env = robot
    # rosrun tf view_frames, as practical 3 writes it: 5 s on /tf, files in the cwd
    book = tmp_path / 'book'
    book.mkdir()
    r = _run(['rosrun', 'tf', 'view_frames'], env, str(book), 30)
    assert r.returncode == 0, 'rosrun tf view_frames failed:\n' + r.stdout + r.stderr
    assert 'Listening to /tf for 5.0 seconds' in r.stdout and 'frames.pdf generated' in r.stdout
    assert (book / 'frames.pdf').read_bytes()[:5] == b'%PDF-'
    gv = (book / 'frames.gv').read_text()
    assert '"base_link" -> "laser"' in gv and '"base_link" -> "imu_link"' in gv, gv

    # Debian's tf executables through the same lookup, once each (no "non-unique" prompt)
    import roslib.packages
    for exe in ('static_transform_publisher', 'tf_echo', 'tf_monitor', 'view_frames'):
        found = roslib.packages.find_node('tf', exe)
        assert len(found) == 1, 'roslaunch pkg="tf" type="%s" finds %s' % (exe, found)
    assert _run(['rospack', 'find', 'tf'], env, None, 30).stdout.strip() == '/usr/share/tf'
    stp = Proc(['rosrun', 'tf', 'static_transform_publisher', '1', '2', '3', '0', '0', '0',
                'base_link', 'probe_frame', '50'], env=env, log=str(tmp_path / 'stp.log'))
    try:
        echo = Proc(['stdbuf', '-oL', 'rosrun', 'tf', 'tf_echo', 'base_link', 'probe_frame'], env=env,
                    log=str(tmp_path / 'echo.log'))
        try:
            wait_for(lambda: 'Translation: [1.000, 2.000, 3.000]' in echo.output(), 30, 0.2,
                     'tf_echo to print the static_transform_publisher transform')
        finally:
            echo.stop()
    finally:
        stp.stop()
    r = _run(['/usr/bin/python3', '-c', 'import tf; print(tf.transformations.quaternion_from_euler(0, 0, 0))'],
             env, None, 30)
    assert r.returncode == 0 and '1.' in r.stdout, r.stderr

    # tf2's tool keeps working
    tf2 = tmp_path / 'tf2'
    tf2.mkdir()
    r = _run(['rosrun', 'tf2_tools', 'view_frames.py'], env, str(tf2), 30)
    assert r.returncode == 0, r.stdout + r.stderr
    assert (tf2 / 'frames.pdf').read_bytes()[:5] == b'%PDF-'
