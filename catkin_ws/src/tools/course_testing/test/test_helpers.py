"""The helpers themselves: a private roscore answers, Xvfb gives a screenshot, groups die."""
import os
import subprocess

from course_testing import Proc, RosCore, Xvfb, screenshot, wait_for


def test_roscore_answers_and_stops(tmp_path):
    core = RosCore(log_dir=str(tmp_path)).start()
    try:
        out = subprocess.run(['rosparam', 'get', '/rosdistro'], env=core.env, capture_output=True,
                             text=True, timeout=30)
        assert out.returncode == 0, out.stderr
        pid = core.proc.pid
    finally:
        core.stop()
    assert not os.path.exists('/proc/%d' % pid) or open('/proc/%d/stat' % pid).read().split()[2] == 'Z'


def test_xvfb_screenshot(tmp_path):
    with Xvfb(320, 240) as x:
        png = screenshot(x.display, str(tmp_path / 'shot.png'))
        ident = subprocess.run(['identify', png], capture_output=True, text=True, check=True).stdout
        assert '320x240' in ident


def test_proc_stop_kills_group(tmp_path):
    p = Proc(['bash', '-c', 'sleep 300 & echo $! > %s; wait' % (tmp_path / 'child')])
    wait_for(lambda: (tmp_path / 'child').exists() and (tmp_path / 'child').read_text().strip(), 60)
    child = int((tmp_path / 'child').read_text())
    p.stop()
    wait_for(lambda: _gone(child), 60, what='child gone')


def test_stop_kills_a_grandchild_in_another_session(tmp_path):
    """roslaunch-style: the child starts a grandchild with setsid; stop() still kills it."""
    pidfile = tmp_path / 'gc'
    p = Proc(['bash', '-c', 'setsid sleep 300 & echo $! > %s; wait' % pidfile])
    wait_for(lambda: pidfile.exists() and pidfile.read_text().strip(), 60)
    gc = int(pidfile.read_text())
    # $! is setsid's pid before it has called setsid(): wait until it has its own group
    wait_for(lambda: os.getpgid(gc) != p.pid, 60, what='the grandchild in a session of its own')
    p.stop()
    wait_for(lambda: _gone(gc), 60, what='grandchild gone')


def test_run_times_out_and_kills_tree(tmp_path):
    from course_testing.proc import run
    pidfile = tmp_path / 'gc'
    rc, timed_out = run(['bash', '-c', 'setsid sleep 300 & echo $! > %s; sleep 300' % pidfile], 1.0,
                        log=str(tmp_path / 'log'))
    assert rc is None and timed_out
    gc = int(pidfile.read_text())
    wait_for(lambda: _gone(gc), 60, what='grandchild gone')


def _gone(pid):
    """Dead: no such process, or a zombie (under the test runner, which is a subreaper,
    orphans wait as zombies until the runner reaps them)."""
    try:
        with open('/proc/%d/stat' % pid) as f:
            return f.read().rsplit(')', 1)[1].split()[0] in ('Z', 'X')
    except OSError:
        return True
