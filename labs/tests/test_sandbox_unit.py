"""Unit tests of the grading sandbox and labs/grade-class pieces (no roscore; bwrap for real)."""
import os
import subprocess

import pytest

from grading import classgrade, sandbox
from grading.checker import foreign_publishers, tampered
from grading.common import LABS_DIR, Criterion
from grading.lab2.rules import topic_owners


@pytest.fixture(scope='module')
def box():
    why = sandbox.probe()
    assert why is None, 'no grading sandbox on this machine: %s' % why
    return sandbox.Sandbox(sandbox.new_uid(), None)


def run_in(box, script, ws_write=False):
    r = subprocess.run(sandbox.netns_prefix() + box.wrap(['bash', '-c', script], writable_ws=ws_write),
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=60, env=box.env(dict(os.environ)))
    return r.returncode, r.stdout.decode(errors='replace')


def test_sandbox_hides_and_protects(box, tmp_path):
    secret = tmp_path / 'other_submission.txt'
    secret.write_text('x')
    rc, out = run_in(box, 'ls %s 2>&1 | wc -w; ls -A %s 2>/dev/null | wc -l; touch %s/x 2>&1 | wc -l; '
                          'id -u; ip -o link | cut -d: -f2'
                     % (secret, os.path.join(LABS_DIR, 'lab2'), sandbox.REPO))
    lines = [l.strip() for l in out.splitlines()]
    assert lines[0] != '1', out                                 # the grader's /tmp: invisible
    assert lines[1] == '0', out                                 # labs/: empty, unreadable
    assert lines[2] == '1', out                                 # the course tree: not writable
    assert lines[3] == str(box.uid), out                        # a user of its own
    assert lines[4:] == ['lo'], out                             # loopback only


def test_sandbox_cannot_write_course_tree_even_as_owner(box):
    rc, out = run_in(box, 'touch %s/x' % sandbox.REPO)
    assert rc != 0 and ('Read-only file system' in out or 'Permission denied' in out), out


def test_sandbox_limits(box):
    rc, out = run_in(box, 'ulimit -u; ulimit -v; ulimit -f; df -m /tmp | tail -1')
    nproc, vmem, fsize, df = out.splitlines()
    assert int(nproc) == sandbox.LIMITS['nproc']
    assert int(vmem) == sandbox.LIMITS['as_mb'] * 1024
    assert int(fsize) == sandbox.LIMITS['fsize_mb'] * 1024
    assert int(df.split()[1]) == sandbox.LIMITS['tmp_mb'], df


def test_sandbox_env_strips_grader(box):
    env = box.env({'GRADING_REPORT': '/tmp/r.json', 'PYTHONPATH': LABS_DIR + ':/usr/lib/x',
                   'ROS_PACKAGE_PATH': os.path.join(LABS_DIR, 'lab2', 'grader') + ':/opt/a', 'HOME': '/root'})
    assert 'GRADING_REPORT' not in env and env['PYTHONPATH'] == '/usr/lib/x'
    assert env['ROS_PACKAGE_PATH'] == '/opt/a' and env['HOME'] == '/tmp/home'
    b = sandbox.Sandbox.from_json(sandbox.Sandbox(61234, '/tmp/ws', student_env={'A': '1'}).to_json())
    e = b.env({'ROS_MASTER_URI': 'http://127.0.0.1:1', 'B': '2'})
    assert e['A'] == '1' and 'B' not in e and e['ROS_MASTER_URI'] == 'http://127.0.0.1:1'


def test_foreign_publisher_is_tampering():
    own = topic_owners('123451')
    obs = {'pubs': {'/ns1_123451/turtlesim': ['/ns1_123451/turtle1/pose'],
                    '/ns2_123451/turtlesim': ['/ns2_123451/turtle1/pose']},
           'srvs': {'/ns1_123451/turtlesim': ['/ns1_123451/spawn'], '/ns2_123451/turtlesim': ['/ns2_123451/spawn']}}
    assert foreign_publishers(own, obs) is None
    obs['pubs']['/ns1_123451/fake'] = ['/ns2_123451/turtle1/pose']
    why = foreign_publishers(own, obs)
    assert why == ('/ns1_123451/fake publishes /ns2_123451/turtle1/pose, '
                   'which only the node providing /ns2_123451/spawn may publish')
    cs = tampered([Criterion('1', 'a', 'b', True)], why)
    assert not cs[0].passed and cs[0].reason['en'] == 'tampering: ' + why


def test_split_ref():
    assert classgrade.split_ref('/a/b@main') == ('/a/b', 'main')
    assert classgrade.split_ref('git@github.com:u/r.git') == ('git@github.com:u/r.git', None)
    assert classgrade.split_ref('git@github.com:u/r.git@v1.0') == ('git@github.com:u/r.git', 'v1.0')
    assert classgrade.split_ref('https://h/r.git') == ('https://h/r.git', None)


def test_roster_rows(tmp_path):
    p = tmp_path / 'r.csv'
    p.write_text('isu,repo,group\n123451,/a,g1\n\n12x,/b,g1\n123451,/c,g2\n223451,,g2\n')
    rows, extra = classgrade.read_roster(str(p))
    assert extra == ['group']
    checked = classgrade.ClassGrader('lab2', str(tmp_path / 'o')).check_rows(rows)
    errs = [e for _l, _r, e in checked]
    assert errs[0] is None
    assert errs[1] == "ISU must be digits only, got '12x'"
    assert errs[2] == 'duplicate ISU 123451 (also on roster line 2)'
    assert errs[3] == 'no repository given'
    bad = tmp_path / 'bad.csv'
    bad.write_text('id,url\n1,/a\n')
    with pytest.raises(classgrade.RosterError, match='must have the columns isu,repo'):
        classgrade.read_roster(str(bad))


def test_fetch_errors(tmp_path):
    with pytest.raises(classgrade.RosterError, match='does not exist'):
        classgrade.fetch(str(tmp_path / 'nope'), str(tmp_path / 'd'))
    with pytest.raises(classgrade.RosterError, match='does not clone'):
        classgrade.fetch('file://%s/nope.git' % tmp_path, str(tmp_path / 'd'))
    (tmp_path / 'plain').mkdir()
    (tmp_path / 'plain' / 'f').write_text('1')
    c1 = classgrade.fetch(str(tmp_path / 'plain'), str(tmp_path / 'd'))
    assert c1.startswith('dir:') and c1 == classgrade.fetch(str(tmp_path / 'plain'), str(tmp_path / 'd'))


def test_probe_names_a_missing_tool(monkeypatch):
    monkeypatch.setattr(sandbox.shutil, 'which', lambda tool: None if tool == 'bwrap' else '/usr/bin/' + tool)
    assert sandbox.probe() == 'bwrap is not installed (Debian package bubblewrap)'


def test_no_sandbox_here_grades_as_self_check(monkeypatch, tmp_path, capsys):
    """Where no sandbox can be made (an unprivileged CI container) labs/grade says so in one
    line and grades without it, marked as a self-check in the report and the JUnit."""
    from grading import cli
    seen = {}

    def fake_grade(lab, isu, repo, timeout, **kw):
        seen.update(kw)
        return [Criterion('0', 'a', 'b', True)]
    monkeypatch.setattr(cli.sandbox, 'probe', lambda: 'No permissions to create a new namespace')
    monkeypatch.setattr(cli, 'grade', fake_grade)
    junit = tmp_path / 'r.xml'
    assert cli.main(['lab2', '--isu', '123451', '--repo', str(tmp_path), '--junit', str(junit)]) == 0
    out, err = capsys.readouterr()
    assert err.strip().splitlines() == ['labs/grade: no sandbox can be made here (No permissions to create a new '
                                        'namespace): grading without one, as a self-check']
    assert seen['sandboxed'] is False
    assert '(self-check: graded without a sandbox (No permissions' in out
    assert 'name="self-check"' in junit.read_text() and 'lab2-123451-self-check' in junit.read_text()
    assert cli.main(['lab2', '--isu', '123451', '--repo', str(tmp_path), '--junit', str(junit),
                     '--require-sandbox']) == 2


FIND_NODE = r'''
import os, subprocess, sys, time
from grading import sandbox
box = sandbox.Sandbox.from_json(sys.argv[1])
p = subprocess.Popen(box.wrap(['bash', '-c', 'sleep 60 & echo $!; sleep 1 & sleep 1 & wait']),
                     stdout=subprocess.PIPE, env=box.env(dict(os.environ)))
try:
    init = sandbox.pidns_of_child(p.pid)
    sandbox.remember_pidns(init)
    inner = int(p.stdout.readline())          # the pid `sleep 60` has inside the sandbox
    pid = sandbox.host_pid(inner)
    if pid is None:
        sys.exit('host_pid(%d) found no process in the sandbox' % inner)
    # `echo $!` may run before the forked child has exec'd sleep: its cmdline is bash's until then
    for _ in range(100):
        with open('/proc/%d/cmdline' % pid, 'rb') as f:
            argv = f.read().split(b'\0')[:2]
        if argv == [b'sleep', b'60']:
            break
        time.sleep(0.05)
    print(init is not None, inner, pid != inner, argv == [b'sleep', b'60'], sandbox.count_procs(init))
finally:
    p.kill()
'''


@pytest.mark.parametrize('ptrace', ['with', 'without'])
def test_grader_finds_sandboxed_processes(box, ptrace):
    """The grader maps a sandboxed node's own PID (what getPid answers) to the process it sees,
    and counts the sandbox's processes (the fork-bomb watch) — also without CAP_SYS_PTRACE, as
    root inside a Docker container is: /proc/PID/ns/* of the sandbox user's processes cannot
    be read there, so the grader saw none of a student's nodes."""
    drop = [] if ptrace == 'with' else ['setpriv', '--inh-caps=-sys_ptrace',
                                        '--bounding-set=-sys_ptrace', '--']
    env = dict(os.environ, PYTHONPATH=LABS_DIR + ':' + os.environ.get('PYTHONPATH', ''))
    r = subprocess.run(drop + ['/usr/bin/python3', '-c', FIND_NODE, box.to_json()], env=env,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, timeout=60, text=True)
    assert r.returncode == 0, r.stdout
    found, inner, mapped, argv_ok, count = r.stdout.split()
    assert (found, mapped, argv_ok) == ('True', 'True', 'True'), r.stdout
    # bwrap's init, bash, sleep 60 and the two sleep 1 (still running: they are read at once)
    assert int(count) >= 3, r.stdout
