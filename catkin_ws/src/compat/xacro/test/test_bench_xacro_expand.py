"""bench/xacro_expand: one line per model with both times and ratios; the scanner target line."""
import os
import re
import shutil
import subprocess

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.abspath(os.path.join(HERE, *[os.pardir] * 5))
BENCH = os.path.join(REPO, 'bench', 'xacro_expand')
ROBOT = os.path.join(HERE, 'fixtures', 'urdf', 'robot.urdf.xacro')


def run(*args):
    return subprocess.run([BENCH] + list(args), capture_output=True, text=True, timeout=120)


def test_model_line_and_scanner_target(tmp_path):
    scanner = tmp_path / 'urdf' / 'chassi_bot.urdf.xacro'
    scanner.parent.mkdir()
    shutil.copy(ROBOT, scanner)
    r = run('--repeat', '3', ROBOT, str(scanner))
    assert r.returncode == 0, r.stdout + r.stderr
    lines = r.stdout.splitlines()
    pat = (r'robot.urdf.xacro: 5 links, \d+ bytes: expand [\d.]+ ms, parse etree [\d.]+ ms '
           r'\(ratio \d+\), minidom [\d.]+ ms \(ratio [\d.]+\); `xacro` process [\d.]+ ms')
    assert any(re.search(pat, l) for l in lines), r.stdout
    m = re.search(r'chassi_bot.urdf.xacro: target "well under a second": in-process [\d.]+ ms = '
                  r'([\d.]+) of 1 s, `xacro` process [\d.]+ ms = ([\d.]+) of 1 s -> (met|NOT met)',
                  r.stdout)
    assert m, r.stdout
    assert 0 < float(m.group(1)) < 1


def test_default_run_without_scanner_model_does_not_fail():
    r = run('--repeat', '1', '--no-cli')
    assert r.returncode == 0, r.stdout + r.stderr
    assert 'urdf_tutorial/urdf/02-cart.urdf.xacro: 6 links' in r.stdout
    assert 'chassi_bot.urdf.xacro' in r.stdout          # either compared or reported absent


def test_broken_model_is_reported():
    r = run('--repeat', '1', '--no-cli', os.path.join(HERE, 'fixtures', 'bad_malformed.xacro'))
    assert r.returncode == 1
    assert 'bad_malformed.xacro: expansion failed:' in r.stdout and 'malformed XML' in r.stdout
    assert 'Traceback' not in r.stderr


def test_bad_arguments():
    r = run('--repeat', '0')
    assert r.returncode == 2 and 'must be positive' in r.stderr
    r = run('/no/such/model.xacro')
    assert r.returncode == 2 and 'no such model file' in r.stderr
