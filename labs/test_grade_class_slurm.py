"""labs/grade-class --backend slurm on a one-node Slurm brought up here (munge, slurmctld,
slurmd; stopped at the end): the same gradebook as the local backend for a short roster.
Slow (a Slurm start-up and two gradings): make test-full only; labs/test-class.sh is the big one."""
import csv
import os
import subprocess

import pytest

from grading.common import LABS_DIR
from grading.slurm import OneNodeSlurm

GRADE_CLASS = os.path.join(LABS_DIR, 'grade-class')


@pytest.mark.full
def test_slurm_and_local_agree(tmp_path):
    roster = tmp_path / 'roster.csv'
    roster.write_text('isu,repo\n123451,%s\n12x,%s\n'
                      % (os.path.join(LABS_DIR, 'lab2', 'reference'), tmp_path / 'nope'))
    books = {}
    with OneNodeSlurm(str(tmp_path / 'cluster'), cpus=2):
        for backend in ('slurm', 'local'):
            out = tmp_path / backend
            p = subprocess.run([GRADE_CLASS, 'lab2', '--roster', str(roster), '--backend', backend, '--out', str(out)],
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=1200)
            assert p.returncode == 0, p.stdout
            with open(out / 'gradebook.csv', newline='') as f:
                books[backend] = [(r['isu'], r['status'], r['score']) for r in csv.DictReader(f)]
    assert books['slurm'] == books['local'] == [('123451', 'passed', '7/7'), ('12x', 'error', '')]
