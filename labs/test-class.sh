#!/bin/bash
# make test-class: labs 1-3 rosters (references, starters, seeded faults, adversarial lab 2
# submissions) through labs/grade-class locally and on a one-node Slurm brought up here
# (munge, slurmctld, slurmd; stopped at the end); both gradebooks right and identical.
# Long (tens of minutes on 2 cores); not part of make test. Args: see labs/grading/testclass.py.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
source "$here/../scripts/env.sh"
cd "$here"
exec /usr/bin/python3 -m grading.testclass "$@"
