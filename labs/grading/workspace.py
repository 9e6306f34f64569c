"""Find the student's package, build it in a fresh overlay workspace, compute the run env."""
import os
import re
import shutil
import subprocess
import xml.etree.ElementTree as ET

import course_runtime

from grading.common import GradeError, LABS_DIR, reason

REPO = os.path.dirname(LABS_DIR)
SKIP_DIRS = {'.git', 'build', 'devel', 'install', 'logs', '.catkin_tools', 'node_modules',
             '__pycache__', '.venv', 'venv'}


def find_packages(root):
    """{package name: directory} of every package.xml under root (shallowest wins)."""
    found = {}
    for d, dirs, files in os.walk(root):
        dirs[:] = sorted(x for x in dirs if x not in SKIP_DIRS and not x.startswith('.'))
        if 'package.xml' in files:
            name = package_name(os.path.join(d, 'package.xml'))
            if name and name not in found:
                found[name] = d
            dirs[:] = []   # packages do not nest
    return found


def package_name(path):
    try:
        return (ET.parse(path).getroot().findtext('name') or '').strip() or None
    except (ET.ParseError, OSError):
        return None


class StepFailed(Exception):
    """A grading step failed; carries a bilingual one-line reason."""

    def __init__(self, why):
        super().__init__(why['en'])
        self.reason = why


def locate(repo, name):
    if not os.path.isdir(repo):
        raise GradeError('repository folder %s does not exist' % repo)
    found = find_packages(repo)
    if name not in found:
        others = ', '.join(sorted(found)) or 'none'
        raise StepFailed(reason('пакет %s не найден в %s (найдены: %s)' % (name, repo, others),
                                'package %s not found in %s (found: %s)' % (name, repo, others)))
    return found[name]


def run_group(cmd, timeout, env=None, cwd=None, log=None):
    """Run cmd in its own process group, output to `log`; on timeout stop its whole process
    tree (rostest's nodes live in sessions of their own). Returns (rc, timed_out)."""
    return course_runtime.run(cmd, timeout, env=env, cwd=cwd, log=log or os.devnull)


def sourced_env(script, base=None, timeout=60, wrap=None):
    """os.environ after `source script` in bash (run through `wrap(cmd)` when given)."""
    cmd = ['bash', '-c', 'source "$1" >/dev/null 2>&1; env -0', 'x', script]
    try:
        r = subprocess.run(wrap(cmd) if wrap else cmd, env=base, stdout=subprocess.PIPE,
                           stderr=subprocess.DEVNULL, timeout=timeout)
    except subprocess.TimeoutExpired:
        raise StepFailed(reason('%s не выполнился за %d с' % (script, timeout),
                                'sourcing %s did not finish within %d s' % (script, timeout)))
    env = {}
    for item in r.stdout.split(b'\0'):
        if b'=' in item:
            k, v = item.split(b'=', 1)
            env[k.decode()] = v.decode('utf-8', 'replace')
    if not env.get('ROS_PACKAGE_PATH'):
        raise GradeError('sourcing %s did not give a ROS environment (is the course workspace built? run make setup)'
                         % script)
    return env


def course_env():
    env = dict(os.environ)
    env.pop('PYTHONHOME', None)
    return sourced_env(os.path.join(REPO, 'scripts', 'env.sh'), env)


def copy_package(src, ws):
    dst = os.path.join(ws, 'src', os.path.basename(os.path.normpath(src)))
    shutil.copytree(src, dst, symlinks=True,
                    ignore=shutil.ignore_patterns(*SKIP_DIRS, '*.pyc'))
    return dst


def build_error(text):
    """The most telling one-line cause in a catkin_make log."""
    lines = [l.rstrip() for l in text.splitlines()]
    m = re.search(r'Could not find a package configuration file provided by\s+"([^"]+)"', text)
    if m:
        return 'missing dependency: find_package(%s) failed (no such package)' % m.group(1)
    for i, l in enumerate(lines):
        if l.startswith('CMake Error') or 'Parse error' in l:
            rest = [x.strip() for x in lines[i + 1:i + 6] if x.strip()]
            return ' '.join([l.strip()] + rest[:2])[:300]
    for l in lines:
        if re.search(r'\berror\b', l, re.I) and 'Invoking' not in l:
            return l.strip()[:300]
    tail = [l for l in lines if l.strip()]
    return (tail[-1] if tail else 'no output')[:300]


def build_overlay(pkg_dir, ws, env, timeout=300.0, box=None, log=None):
    """Copy pkg_dir into ws/src, catkin_make it; return the env with the overlay sourced.
    With a sandbox `box` (grading.sandbox.Sandbox) the build and the sourcing of the overlay
    run inside it, the workspace writable only during the build; the log goes to `log`
    (outside the workspace)."""
    os.makedirs(os.path.join(ws, 'src'), exist_ok=True)
    copy_package(pkg_dir, ws)
    log = log or os.path.join(ws, 'build.log')
    cmd = ['catkin_make', '-C', ws, '-DPYTHON_EXECUTABLE=/usr/bin/python3']
    if box is not None:
        box.chown_tree(ws)
        cmd, env = box.wrap(cmd, writable_ws=True, cwd=ws), box.env(env)
    rc, timed_out = run_group(cmd, timeout, env=env, cwd=ws if box is None else '/', log=log)
    with open(log, errors='replace') as f:
        text = f.read()
    if timed_out:
        raise StepFailed(reason('сборка не завершилась за %d с' % timeout,
                                'the build did not finish within %d s' % timeout))
    if rc != 0:
        cause = build_error(text)
        raise StepFailed(reason('пакет не собирается (catkin_make): %s' % cause,
                                'the package does not build (catkin_make): %s' % cause))
    if box is not None:
        # the overlay's setup files were written by the student's build: source them inside
        return sourced_env(os.path.join(ws, 'devel', 'setup.bash'), env, wrap=box.wrap)
    return sourced_env(os.path.join(ws, 'devel', 'setup.bash'), env)
