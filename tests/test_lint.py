"""The gate's linters, each one test: shellcheck over the shell scripts, clang-format over the
C++, flake8 (pyflakes + pycodestyle) over the Python, and the .editorconfig's basic rules.
All come from Debian (deps/debian.txt); a missing linter fails, never skips. How to run one
linter by hand: CONTRIBUTING.md."""
import os
import re
import subprocess

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHELL_DIRS = ('scripts', 'docker', 'firmware', '.ci')
# never linted: build outputs, installed dependencies, vendored and generated code
SKIP_DIRS = {'.git', '.deps', 'build', 'devel', 'install', 'logs', '.catkin_tools', 'workspace',
             'node_modules', 'vendor', '__pycache__', '.pytest_cache'}
CXX_EXTENSIONS = ('.cpp', '.cc', '.h', '.hpp')
# written by a program, in that program's layout: rosrun space_scanner_hw calibrate_accel
CXX_GENERATED = {'firmware/sketches/space_scanner_base/accel_calibration.h'}


def source_files(extensions, top=REPO):
    """Paths (relative to REPO) of the files under `top` ending in `extensions`, outside
    SKIP_DIRS (walks the tree: the course image has no .git)."""
    found = []
    for root, dirs, files in os.walk(top):
        dirs[:] = sorted(d for d in dirs if d not in SKIP_DIRS)
        found += [os.path.relpath(os.path.join(root, f), REPO) for f in sorted(files)
                  if f.endswith(extensions)]
    return found


def _is_shell(path):
    if path.endswith(('.sh', '.bash')):
        return True
    try:
        with open(path, 'rb') as f:
            first = f.readline(200)
    except OSError:
        return False
    return first.startswith(b'#!') and first.split()[-1].rsplit(b'/', 1)[-1] in (b'sh', b'bash')


def shell_scripts():
    """Every shell script under scripts/, docker/, firmware/ and .ci/ (by extension or #!)."""
    found = []
    for top in SHELL_DIRS:
        for root, dirs, files in os.walk(os.path.join(REPO, top)):
            dirs[:] = [d for d in dirs if d not in ('build', 'node_modules', '__pycache__')]
            found += [os.path.join(root, f) for f in files if _is_shell(os.path.join(root, f))]
    return sorted(found)


def test_shellcheck():
    scripts = shell_scripts()
    rel = [os.path.relpath(p, REPO) for p in scripts]
    assert 'scripts/setup.sh' in rel and '.ci/run' in rel and 'docker/docker_run.bash' in rel, rel
    # -x -P SCRIPTDIR: follow `source`d files relative to the script (docker/common.bash)
    r = subprocess.run(['shellcheck', '-x', '-P', 'SCRIPTDIR', '-f', 'gcc'] + rel, cwd=REPO,
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, 'shellcheck:\n' + (r.stdout + r.stderr)[-6000:]


def test_clang_format():
    """The C++ follows the .clang-format nearest to each file (the top-level one: ROS style;
    ode_sim, the navigation cores and bench/ have their own): `clang-format -i FILE` fixes it."""
    files = [f for f in source_files(CXX_EXTENSIONS) if f not in CXX_GENERATED]
    assert len(files) > 100 and 'catkin_ws/src/control/hardware_interface/include/hardware_interface/robot_hw.h' \
        in files, len(files)
    bad = []
    for i in range(0, len(files), 50):
        r = subprocess.run(['clang-format', '--style=file', '--dry-run', '-Werror',
                            '--ferror-limit=1'] + files[i:i + 50], cwd=REPO, capture_output=True,
                           text=True, timeout=600)
        if r.returncode != 0:
            bad += sorted(set(re.findall(r'^(\S+?):\d+:\d+: error', r.stderr, re.M)))
    assert not bad, 'not formatted as .clang-format says (clang-format -i FILE fixes it): %s' % bad


def _editorconfig_sections():
    """[(fnmatch patterns, {property: value})] of the top-level .editorconfig, in order;
    `{a,b}` alternatives expanded (the only glob feature it uses beyond fnmatch's)."""
    sections = []
    with open(os.path.join(REPO, '.editorconfig')) as f:
        for line in f:
            line = line.split('#')[0].strip()
            if line.startswith('[') and line.endswith(']'):
                glob = line[1:-1]
                m = re.match(r'^(.*)\{([^}]*)\}(.*)$', glob)
                pats = [m.group(1) + alt + m.group(3) for alt in m.group(2).split(',')] if m else [glob]
                sections.append((pats, {}))
            elif '=' in line and sections:
                k, v = (x.strip() for x in line.split('=', 1))
                sections[-1][1][k] = v
    return sections


def test_editorconfig():
    """The files of every kind .editorconfig names (by pattern other than `*`) keep its rules:
    UTF-8, LF line ends, a final newline, no trailing whitespace, indentation by spaces
    (Makefiles: tabs)."""
    import fnmatch
    sections = _editorconfig_sections()
    assert sections and sections[0][0] == ['*'] and sections[0][1]['end_of_line'] == 'lf'
    problems, checked = [], 0
    for root, dirs, files in os.walk(REPO):
        dirs[:] = [d for d in dirs if d not in SKIP_DIRS]
        for name in files:
            props, named = {}, False
            for pats, p in sections:
                if any(fnmatch.fnmatchcase(name, pat) for pat in pats):
                    props.update(p)
                    named = named or pats != ['*']
            if not named:
                continue
            path = os.path.join(root, name)
            rel = os.path.relpath(path, REPO)
            with open(path, 'rb') as f:
                data = f.read()
            checked += 1
            try:
                data.decode('utf-8')
            except UnicodeDecodeError as e:
                problems.append('%s: not UTF-8 (%s)' % (rel, e.reason))
                continue
            if not data:
                continue
            if props.get('end_of_line') == 'lf' and b'\r' in data:
                problems.append('%s: CR line ends' % rel)
            if props.get('insert_final_newline') == 'true' and not data.endswith(b'\n'):
                problems.append('%s: no newline at the end' % rel)
            lines = data.split(b'\n')
            if props.get('trim_trailing_whitespace') == 'true':
                n = [i + 1 for i, l in enumerate(lines) if l != l.rstrip(b' \t')]
                if n:
                    problems.append('%s:%d: trailing whitespace' % (rel, n[0]))
            if props.get('indent_style') == 'space':
                n = [i + 1 for i, l in enumerate(lines) if l.startswith(b'\t')]
                if n:
                    problems.append('%s:%d: indented with a tab' % (rel, n[0]))
    assert checked > 1000, checked
    assert not problems, '\n'.join(problems[:50])


def python_files():
    """Every .py file and every Python script without the extension (a #! line naming python),
    outside SKIP_DIRS."""
    found = []
    for root, dirs, files in os.walk(REPO):
        dirs[:] = sorted(d for d in dirs if d not in SKIP_DIRS)
        for name in sorted(files):
            path = os.path.join(root, name)
            if name.endswith('.py'):
                found.append(os.path.relpath(path, REPO))
            elif '.' not in name:
                with open(path, 'rb') as f:
                    first = f.readline(200)
                if first.startswith(b'#!') and b'python' in first:
                    found.append(os.path.relpath(path, REPO))
    return found


def test_flake8():
    """pyflakes + pycodestyle over the Python, with the settings of .flake8 (120 columns)."""
    files = python_files()
    assert len(files) > 500 and 'catkin_ws/src/navigation/amcl/scripts/amcl' in files, len(files)
    r = subprocess.run(['/usr/bin/python3', '-m', 'flake8'] + files, cwd=REPO, capture_output=True,
                       text=True, timeout=900)
    assert r.returncode == 0 and not r.stdout, 'flake8 (.flake8):\n' + (r.stdout + r.stderr)[-8000:]
