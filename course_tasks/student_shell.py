"""Helpers for the course-task tests: replay a student's terminal session.

A test makes a fresh catkin workspace in a temporary directory, runs the chapter's commands
(`catkin init`, `catkin_create_pkg`, `catkin build`, `catkin_make`, `rosrun`, `roslaunch`,
`rostopic ...`) as child processes with the environment a student's shell would have after
`source scripts/env.sh` and `source devel/setup.bash`, and checks what those commands print.
"""
import os
import re
import shutil
import signal
import subprocess
import textwrap
import time

import yaml

from course_testing import Proc, wait_for

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ENV_SH = os.path.join(REPO, 'scripts', 'env.sh')
MASTER_VARS = ('ROS_MASTER_URI', 'ROS_IP', 'ROS_LOG_DIR')


def shell_env(*setup_files):
    """os.environ as a bash shell has it after `source scripts/env.sh; source <setup_files>`."""
    script = 'source "%s" >/dev/null 2>&1\n' % ENV_SH
    for f in setup_files:
        script += 'source "%s" || exit 3\n' % f
    script += 'env -0\n'
    out = subprocess.run(['bash', '-c', script], stdout=subprocess.PIPE, check=True,
                         timeout=60).stdout.decode()
    env = dict(item.split('=', 1) for item in out.split('\0') if '=' in item)
    env['PYTHONUNBUFFERED'] = '1'
    return env


def with_master(env, roscore, xvfb=None):
    """`env` pointed at a private roscore (and at an Xvfb display when given)."""
    env = dict(env)
    env.pop('ROS_HOSTNAME', None)
    for k in MASTER_VARS:
        env[k] = roscore.env[k]
    if xvfb is not None:
        env['DISPLAY'] = xvfb.display
        env.pop('QT_QPA_PLATFORM', None)
    return env


def sh(cmd, env, cwd=None, timeout=300, check=True):
    """Run a command (list, or a string for bash -c); return its combined output."""
    if isinstance(cmd, str):
        cmd = ['bash', '-c', cmd]
    if cwd is not None:
        env = dict(env, PWD=str(cwd))    # catkin_make takes its base path from $PWD
    p = subprocess.Popen(cmd, env=env, cwd=cwd, stdout=subprocess.PIPE,
                         stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                         start_new_session=True)
    try:
        out, _ = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        out, _ = p.communicate()
        raise AssertionError('%s: still running after %d s; output:\n%s'
                             % (' '.join(cmd), timeout, out.decode(errors='replace')[-3000:]))
    text = out.decode(errors='replace')
    if check and p.returncode != 0:
        raise AssertionError('%s exited with %d; output:\n%s'
                             % (' '.join(cmd), p.returncode, text[-3000:]))
    return text


def sh_rc(cmd, env, cwd=None, timeout=60):
    """(exit code, stdout, stderr) of a command."""
    p = subprocess.run(cmd, env=env, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                       stdin=subprocess.DEVNULL, timeout=timeout, start_new_session=True)
    return p.returncode, p.stdout.decode(errors='replace'), p.stderr.decode(errors='replace')


def make_workspace(root):
    """`mkdir workspace; cd workspace; mkdir src; catkin init` under root; returns its path."""
    ws = os.path.join(str(root), 'workspace')
    os.makedirs(os.path.join(ws, 'src'))
    out = sh(['catkin', 'init'], shell_env(), cwd=ws, timeout=120)
    assert 'Initialized new catkin workspace' in out or 'Workspace configuration appears valid' in out, out
    return ws


def create_package(ws, pkg, deps, dirs, reference, files):
    """`catkin_create_pkg PKG DEPS…` in ws/src, `mkdir DIRS…` in it, and the chapter's files
    (`files`: {subdir: [names]}) copied from the reference package, standing for what the
    student types from the text. Returns (package path, catkin_create_pkg output)."""
    src = os.path.join(ws, 'src')
    out = sh(['catkin_create_pkg', pkg] + list(deps), shell_env(), cwd=src)
    path = os.path.join(src, pkg)
    sh(['mkdir'] + list(dirs), shell_env(), cwd=path)
    for d, names in files.items():
        for name in names:
            shutil.copy2(os.path.join(reference, d, name), os.path.join(path, d, name))
    return path, out


def readme_listing(readme, start):
    """The fenced code block of a task text whose (dedented) text begins with `start`."""
    with open(readme) as f:
        text = f.read()
    for m in re.finditer(r'```\w*\n(.*?)```', text, re.S):
        block = textwrap.dedent(m.group(1))
        if block.startswith(start):
            return block
    raise AssertionError('no listing starting with %r in %s' % (start, readme))


def write_script(path, text):
    """A listing typed into an executable script file (chmod +x)."""
    with open(path, 'w') as f:
        f.write(text)
    os.chmod(path, 0o755)


def catkin_build(ws):
    """`catkin build` in ws with the student's shell environment; returns the output."""
    return sh(['catkin', 'build', '--no-status', '--no-notify',
               '-DPYTHON_EXECUTABLE=/usr/bin/python3'], shell_env(), cwd=ws, timeout=600)


def overlay_env(ws):
    """The environment after `source devel/setup.bash` of workspace ws."""
    return shell_env(os.path.join(ws, 'devel', 'setup.bash'))


def launch(cmd, env, log_path):
    """Start a long-running command (roslaunch, rosrun, ...) logging to log_path."""
    return Proc(cmd, env=env, log=str(log_path))


def echo_once(topic, env, timeout=30.0):
    """One message of `topic` as a dict (`rostopic echo -n 1 topic`)."""
    out = sh(['rostopic', 'echo', '-n', '1', topic], env, timeout=timeout)
    return yaml.safe_load(out.split('\n---')[0])


def wait_topic(topic, env, timeout=90.0, proc=None):
    """Wait until `topic` delivers a message; return it as a dict. On failure the message
    includes the end of `proc`'s log (the roslaunch that should publish it)."""
    deadline = time.monotonic() + timeout
    last = None
    while time.monotonic() < deadline:
        try:
            # one echo for the whole wait (it waits for the publisher itself): restarting it every
            # few seconds never gets through when starting rostopic alone takes that long
            return echo_once(topic, env, timeout=max(1.0, deadline - time.monotonic()))
        except AssertionError as e:
            last = e
            time.sleep(0.3)
    log = ('\n--- log of %s:\n%s' % (' '.join(proc.cmd), proc.output()[-3000:])) if proc else ''
    raise AssertionError('no message on %s within %.0f s (%s)%s' % (topic, timeout, last, log))


def wait_output(proc, text, timeout=60.0):
    """Wait until a Proc started with a log prints `text`; fail with its output if it exits."""
    def seen():
        out = proc.output()
        if text in out:
            return out
        if not proc.alive():
            raise AssertionError('%s exited (%s) before printing %r; output:\n%s'
                                 % (proc.cmd, proc.popen.poll(), text, out[-3000:]))
        return None
    try:
        return wait_for(seen, timeout, 0.1, '%r in the output of %s' % (text, ' '.join(proc.cmd)))
    except TimeoutError as e:
        raise AssertionError('%s; output so far:\n%s' % (e, proc.output()[-3000:]))


def run_probe(code, env, timeout=60.0):
    """Run a small rospy script (child process, Debian python) and return its stdout as YAML."""
    out = sh(['/usr/bin/python3', '-c', code], env, timeout=timeout)
    return yaml.safe_load(out.strip().splitlines()[-1])


def stop_all(*procs):
    for p in procs:
        if p is not None:
            p.stop()


def unique_colours(png):
    """Number of distinct colours in an image (ImageMagick `identify -format %k`)."""
    out = subprocess.run(['identify', '-format', '%k', png], stdout=subprocess.PIPE, check=True,
                         timeout=60).stdout.decode()
    return int(out.strip())
