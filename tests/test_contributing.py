"""CONTRIBUTING.md's commands exist: every command of its ```bash blocks names a program on the
course's PATH (or a file of the repository, a make target, a ROS package's file), every
repository path it names exists, and each `pytest -k` filter selects tests."""
import os
import re
import shlex
import subprocess

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DOC = os.path.join(REPO, 'CONTRIBUTING.md')
BUILTINS = {'source', 'cd', 'export'}


def _env():
    """The environment of a shell that ran `source scripts/env.sh`."""
    out = subprocess.run(['bash', '-c', 'source scripts/env.sh >/dev/null && env -0'], cwd=REPO,
                         capture_output=True, timeout=60, check=True).stdout
    return dict(kv.split('=', 1) for kv in out.decode().split('\0') if '=' in kv)


def commands():
    """(line, argv) of every command in the file's ```bash blocks (comments dropped)."""
    text = open(DOC).read()
    found = []
    for block in re.findall(r'```bash\n(.*?)```', text, re.S):
        for line in block.splitlines():
            line = line.split(' #')[0].strip()
            if line and not line.startswith('#'):
                found.append((line, shlex.split(line)))
    return found


def _which(name, env):
    for d in env['PATH'].split(':'):
        if os.access(os.path.join(d, name), os.X_OK):
            return True
    return False


def _make_targets():
    with open(os.path.join(REPO, 'Makefile')) as f:
        return set(re.findall(r'^([a-z][\w-]*):', f.read(), re.M))


def test_the_file_names_commands():
    argvs = [argv for _line, argv in commands()]
    programs = {a[0] for a in argvs}
    # the sections the next engineer looks for: setup, one test, the linters, the bench
    assert {'make', 'bash', 'rostest', 'shellcheck', 'clang-format', 'source'} <= programs, programs
    assert ['make', 'bench'] in argvs and ['make', 'test'] in argvs


@pytest.mark.parametrize('line,argv', commands(), ids=[c[0][:60] for c in commands()])
def test_command_exists(line, argv):
    env = _env()
    prog = argv[0]
    if prog in BUILTINS:
        pass
    elif '/' in prog:
        path = os.path.join(REPO, prog)
        assert os.path.isfile(path) and os.access(path, os.X_OK), '%s: not an executable file' % prog
    elif prog == '/usr/bin/python3' or prog == 'python3':
        pass
    else:
        assert _which(prog, env), '%s: not on the PATH of scripts/env.sh' % prog
    if prog == 'make':
        assert argv[1] in _make_targets(), 'no make target %s' % argv[1]
    if prog == 'rostest':
        r = subprocess.run(['rospack', 'find', argv[1]], env=env, capture_output=True, text=True,
                           timeout=60)
        assert r.returncode == 0, r.stderr
        assert os.path.isfile(os.path.join(r.stdout.strip(), 'test', argv[2])), line
    # the repository's files it names (a script, a test file, a folder to lint)
    for arg in argv[1:]:
        if '/' in arg and not arg.startswith(('-', '$')) and '=' not in arg:
            assert os.path.exists(os.path.join(REPO, arg)), '%s: %s does not exist' % (line, arg)
    if '-k' in argv and argv[0] == 'bash':
        expr = argv[argv.index('-k') + 1]
        assert re.match(r'^\w+$', expr), expr
        assert _test_names_containing(expr), 'pytest -k %s selects no test file or function' % expr


def _test_names_containing(word):
    """Test files (test_*.py) or test functions whose name contains `word`."""
    hits = []
    for top in ('tests', 'catkin_ws/src', 'labs', 'course_tasks', 'bench'):
        for root, dirs, files in os.walk(os.path.join(REPO, top)):
            dirs[:] = [d for d in dirs if d not in ('build', 'devel', 'node_modules', '__pycache__')]
            for f in files:
                if f.startswith('test_') and f.endswith('.py'):
                    if word in f:
                        hits.append(f)
                    elif re.search(r'^def test_\w*%s' % re.escape(word),
                                   open(os.path.join(root, f), encoding='utf-8').read(), re.M):
                        hits.append(f)
    return hits


def test_the_paths_it_names_exist():
    text = open(DOC).read()
    paths = re.findall(r'`((?:catkin_ws|labs|bench|tests|scripts|firmware|deps)/[^` ]+)`', text)
    assert len(paths) >= 8, paths
    missing = [p for p in paths if not os.path.exists(os.path.join(REPO, p.rstrip('/')))]
    assert not missing, missing
