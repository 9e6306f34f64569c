"""Test helpers shared by the simulation packages' tests and the course-task replays:
start a launch file on a test's private roscore, and run the probes of `sim_probe` as child
processes (a rospy node per probe, so one pytest process can use several masters)."""
import os
import subprocess

import yaml

from course_testing import Proc


def ros_env(roscore, base=None):
    """`base` (default: this process's environment) pointed at the test's roscore, headless."""
    env = dict(base if base is not None else os.environ)
    env.pop('ROS_HOSTNAME', None)
    for k in ('ROS_MASTER_URI', 'ROS_IP', 'ROS_LOG_DIR'):
        if k in roscore.env:
            env[k] = roscore.env[k]
    env.pop('DISPLAY', None)
    env['PYTHONUNBUFFERED'] = '1'
    return env


def roslaunch(pkg, launch_file, args, env, log):
    """`roslaunch pkg launch_file args...` in the background; stop it with .stop()."""
    return Proc(['roslaunch', pkg, launch_file] + list(args), env=env, log=str(log))


def probe(args, env, timeout=120.0, proc=None):
    """Run `python3 -m course_testing.sim_probe args...` and return its YAML output.
    On failure the assertion names the probe and shows the end of `proc`'s log."""
    cmd = ['/usr/bin/python3', '-m', 'course_testing.sim_probe'] + [str(a) for a in args]
    try:
        p = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           stdin=subprocess.DEVNULL, timeout=timeout, start_new_session=True)
    except subprocess.TimeoutExpired:
        raise AssertionError('%s: no answer within %.0f s%s' % (' '.join(args), timeout, _log(proc)))
    if p.returncode != 0:
        raise AssertionError('%s failed: %s%s' % (' '.join(str(a) for a in args),
                                                  p.stderr.decode(errors='replace').strip()[-2000:],
                                                  _log(proc)))
    return yaml.safe_load(p.stdout.decode().strip().splitlines()[-1])


def _log(proc):
    if proc is None:
        return ''
    return '\n--- log of %s:\n%s' % (' '.join(proc.cmd), proc.output()[-4000:])


def rosrun_out(args, env, timeout=60.0):
    """(exit code, combined output) of a short command such as `rosservice call ...`."""
    p = subprocess.run(args, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       stdin=subprocess.DEVNULL, timeout=timeout, start_new_session=True)
    return p.returncode, p.stdout.decode(errors='replace')
