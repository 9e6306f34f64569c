"""The bench script runs end to end (short settings) and prints its ratio lines."""
import os
import re
import subprocess

import pytest

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), *[os.pardir] * 5))


@pytest.mark.full
def test_bench_prints_rate_and_latency_ratios():
    env = dict(os.environ)
    env.pop('DISPLAY', None)
    r = subprocess.run([os.path.join(REPO, 'bench', 'turtlesim_rate'), '--seconds', '3',
                        '--samples', '30'], env=env, capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    m = re.search(r'\[headless\] pose rate: ([\d.]+) Hz \(ratio ([\d.]+) of 62.5 Hz', r.stdout)
    assert m, r.stdout
    assert abs(float(m.group(2)) - 1.0) < 0.05
    assert re.search(r'latency over 30 samples: median [\d.]+ ms', r.stdout)


def test_bench_rejects_bad_arguments():
    r = subprocess.run([os.path.join(REPO, 'bench', 'turtlesim_rate'), '--samples', '0'],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 2
    assert 'must be positive' in r.stderr and 'Traceback' not in r.stderr
