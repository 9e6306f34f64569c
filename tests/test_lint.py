"""The gate's linters, each one test: shellcheck over the shell scripts, clang-format over the
C++, flake8 (pyflakes + pycodestyle) over the Python, and the .editorconfig's basic rules.
All come from Debian (deps/debian.txt); a missing linter fails, never skips. How to run one
linter by hand: CONTRIBUTING.md."""
import os
import subprocess

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHELL_DIRS = ('scripts', 'docker', 'firmware', '.ci')


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
