"""The machine the textbook assumes (issue 29, section 2), tried as the book prints it.

- `python` is Python 3 (Debian's python-is-python3): the book's first listings
  (T §2.10-2.11, `my_publisher.py` / `my_subscriber.py`, typed as printed into course_tasks/book/)
  start with `#!/usr/bin/env python` and run through `rosrun` with nothing but PATH=/usr/bin:/bin.
- rosdep as T §1.6 teaches it: `rosdep update` works offline (every registered source and the
  rosdistro index are local files: the course's deps/rosdep/), and
  `rosdep install --from-paths <pkg> --ignore-src -y --simulate` finds every key of every course,
  lab and diploma package and has nothing left to install.
"""
import glob
import importlib.util
import os
import re
import shutil
import subprocess

import pytest
import yaml

_spec = importlib.util.spec_from_file_location(
    'course_tasks_student_shell_machine', os.path.join(os.path.dirname(__file__), 'student_shell.py'))
S = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(S)

HERE = os.path.dirname(os.path.abspath(__file__))
BOOK = os.path.join(HERE, 'book')
RULES = os.path.join(S.REPO, 'deps', 'rosdep', 'ros-course.yaml')
LISTS = '/etc/ros/rosdep/sources.list.d'
DEBIAN_RULES = '/usr/share/python3-rosdep2/debian.yaml'

# every course, lab and diploma package (each its own `--from-paths`: the labs' starter and
# reference share a package name)
PACKAGE_DIRS = sorted(
    os.path.dirname(p) for pattern in ('catkin_ws/src/course/*/package.xml',
                                       'catkin_ws/src/space_scanner/*/package.xml',
                                       'course_tasks/task_*/*/*/package.xml',
                                       'labs/lab*/*/package.xml',
                                       'labs/lab*/*/*/package.xml')
    for p in glob.glob(os.path.join(S.REPO, pattern)))


def test_python_is_python3():
    assert os.path.realpath('/usr/bin/python').startswith('/usr/bin/python3'), \
        '/usr/bin/python is not Python 3: install python-is-python3 (deps/debian.txt, scripts/setup.sh)'


def test_env_python_listing_runs_through_rosrun(roscore, tmp_path):
    """T §2.10-2.11: the package's scripts as printed, `rosrun` with PATH=/usr/bin:/bin."""
    src = tmp_path / 'src'
    src.mkdir()
    S.sh(['catkin_create_pkg', 'my_robot_controller', 'rospy', 'std_msgs'], S.shell_env(), cwd=src)
    scripts = src / 'my_robot_controller' / 'scripts'
    scripts.mkdir()
    for name in ('my_publisher.py', 'my_subscriber.py'):
        with open(os.path.join(BOOK, name)) as f:
            text = f.read()
        assert text.startswith('#!/usr/bin/env python\n'), name
        S.write_script(str(scripts / name), text)
    env = S.with_master(S.shell_env(), roscore)
    env['PATH'] = '/usr/bin:/bin'
    env['ROS_PACKAGE_PATH'] = '%s:%s' % (src, env['ROS_PACKAGE_PATH'])
    pub = S.launch(['rosrun', 'my_robot_controller', 'my_publisher.py'], env, tmp_path / 'pub.log')
    sub = S.launch(['rosrun', 'my_robot_controller', 'my_subscriber.py'], env, tmp_path / 'sub.log')
    try:
        msg = S.wait_topic('/chatter', env, timeout=60, proc=pub)
        assert re.match(r'hello world \d+(\.\d+)?$', msg['data']), msg
        out = S.wait_output(sub, 'I heard hello world', timeout=60)
        assert 'SyntaxError' not in out and 'Traceback' not in out, out
    finally:
        S.stop_all(sub, pub)


def _keys(package_dir):
    from catkin_pkg.package import parse_package
    p = parse_package(os.path.join(package_dir, 'package.xml'))
    p.evaluate_conditions({'ROS_PYTHON_VERSION': '3', 'ROS_DISTRO': 'noetic', 'ROS_VERSION': '1'})
    deps = (p.build_depends + p.buildtool_depends + p.build_export_depends + p.buildtool_export_depends
            + p.exec_depends + p.test_depends + p.doc_depends)
    return {d.name for d in deps if d.evaluated_condition is not False}


def test_course_rules_define_every_key():
    """Each key of a course, lab or diploma package.xml is in deps/rosdep/ros-course.yaml."""
    with open(RULES) as f:
        rules = yaml.safe_load(f)
    assert len(PACKAGE_DIRS) >= 25, PACKAGE_DIRS
    missing = {}
    for d in PACKAGE_DIRS:
        for key in sorted(_keys(d) - set(rules)):
            missing.setdefault(key, []).append(os.path.relpath(d, S.REPO))
    assert not missing, 'rosdep keys missing from deps/rosdep/ros-course.yaml: %s' % missing
    for key, rule in rules.items():
        assert set(rule) == {'debian'}, key
        assert isinstance(rule['debian'], (list, dict)), key


def test_course_rules_define_every_workspace_key():
    """The book's `rosdep install --from-paths src --ignore-src` in catkin_ws (scripts/setup.sh runs
    it) needs every key of every workspace package too: in the course's rules or in Debian's own
    (python3-rosdep2's debian.yaml, registered next to them)."""
    with open(RULES) as f:
        rules = dict(yaml.safe_load(f))
    with open(DEBIAN_RULES) as f:
        rules.update(yaml.safe_load(f))
    missing = {}
    for p in sorted(glob.glob(os.path.join(S.REPO, 'catkin_ws', 'src', '**', 'package.xml'), recursive=True)):
        d = os.path.dirname(p)
        for key in sorted(_keys(d) - set(rules)):
            missing.setdefault(key, []).append(os.path.relpath(d, S.REPO))
    assert not missing, 'rosdep keys missing from deps/rosdep/ros-course.yaml: %s' % missing


@pytest.fixture(scope='module')
def rosdep_env(tmp_path_factory):
    """The student's shell with a fresh rosdep cache after `rosdep update` (ROS_HOME: private)."""
    home = tmp_path_factory.mktemp('ros_home')
    env = dict(S.shell_env(), ROS_HOME=str(home), PATH='/usr/bin:/bin')
    assert shutil.which('rosdep', path=env['PATH']), 'no rosdep: install python3-rosdep2 (deps/debian.txt)'
    out = S.sh(['rosdep', 'update'], env, timeout=120)
    assert 'ERROR' not in out, out
    assert 'Hit file://%s' % RULES in out, out
    return env


def test_rosdep_sources_are_local(rosdep_env):
    """scripts/setup.sh registered the course's rules first and left no internet source."""
    course = os.path.join(LISTS, '05-ros-course.list')
    assert os.path.isfile(course), '%s missing: run scripts/setup.sh' % course
    with open(course) as f:
        assert 'yaml file://%s' % RULES in f.read()
    for path in glob.glob(os.path.join(LISTS, '*.list')):
        with open(path) as f:
            remote = [l for l in f if re.match(r'\s*[^#\s].*\bhttps?://', l)]
        assert not remote, '%s lists internet sources (rosdep update needs the network): %s' % (path, remote)
    rc, out, err = S.sh_rc(['/usr/bin/python3', '-c', 'import rosdistro; print(rosdistro.get_index_url())'],
                           rosdep_env)
    assert out.strip() == 'file://%s' % os.path.join(S.REPO, 'deps', 'rosdep', 'index-v4.yaml'), (out, err)


def test_rosdep_resolves_to_debian_names(rosdep_env):
    out = S.sh(['rosdep', 'resolve', 'roscpp', 'cv_bridge', 'python3-numpy', 'turtlesim'], rosdep_env)
    assert 'libroscpp-dev' in out and 'python3-cv-bridge' in out and 'python3-numpy' in out, out
    assert 'ros-noetic' not in out, out
    assert '#ROSDEP[turtlesim]' in out, out


@pytest.mark.parametrize('package_dir', [os.path.relpath(d, S.REPO) for d in PACKAGE_DIRS])
def test_rosdep_install_simulate(rosdep_env, package_dir):
    """`rosdep install --from-paths <pkg> --ignore-src -y --simulate`: every key located, nothing to install."""
    path = os.path.join(S.REPO, package_dir)
    rc, out, err = S.sh_rc(['rosdep', 'install', '--from-paths', path, '--ignore-src', '-y', '--simulate'],
                           rosdep_env, timeout=120)
    assert rc == 0 and 'Cannot locate rosdep definition' not in out + err, out + err
    assert not [l for l in out.splitlines() if l.strip() and not l.startswith('#')], \
        'rosdep would install packages for %s:\n%s' % (package_dir, out)
    rc, out, err = S.sh_rc(['rosdep', 'check', '--from-paths', path, '--ignore-src'], rosdep_env, timeout=120)
    assert rc == 0 and re.search(r'All system dependencies have been satisf(i)?ied', out), out + err


def test_rosdep_install_in_the_workspace_as_printed(rosdep_env):
    """T §1.6 word for word in catkin_ws: `rosdep install --from-paths src --ignore-src` (-y)."""
    ws = os.path.join(S.REPO, 'catkin_ws')
    rc, out, err = S.sh_rc(['rosdep', 'install', '--from-paths', 'src', '--ignore-src', '-y', '--simulate'],
                           rosdep_env, cwd=ws, timeout=300)
    assert rc == 0 and 'Cannot locate rosdep definition' not in out + err, out + err
    assert not [l for l in out.splitlines() if l.strip() and not l.startswith('#')], out


def test_rules_define_every_key_of_debians_ros_packages():
    """rospack asks rosdep about every dependency that is not a package (`rospack depends1 PKG`
    of a student's package walks Debian's catkin, rospy, ...): every key the package.xml of an
    installed Debian ROS package names must be known, or rospack fails with "rosdep claims that
    it is not a system dependency"."""
    with open(RULES) as f:
        rules = dict(yaml.safe_load(f))
    with open(DEBIAN_RULES) as f:
        rules.update(yaml.safe_load(f))
    listed = subprocess.run(['rospack', 'list'], capture_output=True, text=True, check=True)
    installed = dict(line.split(' ', 1) for line in listed.stdout.splitlines())
    system = {n: d for n, d in installed.items() if d.startswith('/usr/')}
    assert len(system) >= 50, system
    missing = {}
    for name, d in sorted(system.items()):
        if not os.path.exists(os.path.join(d, 'package.xml')):
            continue
        for key in sorted(_keys(d) - set(rules) - set(installed)):
            missing.setdefault(key, []).append(name)
    assert not missing, 'rosdep keys missing from deps/rosdep/ros-course.yaml: %s' % missing


def test_rospack_depends_of_a_package_on_debians_ros_is_clean():
    """`rospack depends rospy` resolves Debian's whole tree without a rosdep error line."""
    r = subprocess.run(['rospack', 'depends', 'rospy'], capture_output=True, text=True)
    assert r.returncode == 0 and 'Error' not in r.stderr, r.stderr[-2000:]
    assert 'roscpp' in r.stdout.split() or 'rosgraph' in r.stdout.split(), r.stdout
