#!/usr/bin/env bash
# Run every benchmark in bench/: each prints ratios measured in one run (not a pass/fail gate).
set -uo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# shellcheck disable=SC1091
source "$REPO/scripts/env.sh"
unset DISPLAY
status=0
# a benchmark is an executable file bench/NAME or a folder bench/NAME/ with an executable `run`
# (those record a simulated drive first: a longer time limit)
for b in "$REPO"/bench/*; do
    limit=600
    if [ -d "$b" ] && [ -x "$b/run" ]; then
        run="$b/run"; limit=1800
    elif [ -f "$b" ] && [ -x "$b" ]; then
        run="$b"
    else
        continue
    fi
    echo "=== bench/$(basename "$b")"
    timeout "$limit" "$run" || { echo "bench/$(basename "$b") failed (exit $?)"; status=1; }
done
exit $status
