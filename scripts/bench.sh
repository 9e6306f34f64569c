#!/usr/bin/env bash
# Run every benchmark in bench/: each prints ratios measured in one run (not a pass/fail gate).
set -uo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# shellcheck disable=SC1091
source "$REPO/scripts/env.sh"
unset DISPLAY
status=0
for b in "$REPO"/bench/*; do
    [ -f "$b" ] && [ -x "$b" ] || continue
    echo "=== bench/$(basename "$b")"
    timeout 600 "$b" || { echo "bench/$(basename "$b") failed (exit $?)"; status=1; }
done
exit $status
