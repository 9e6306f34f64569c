#!/usr/bin/env bash
# Every unit test (pytest), every rostest, headless; ends with "N passed, N failed[, N skipped]".
#   scripts/test.sh            the gate (make test)
#   scripts/test.sh --full     also the slow tests marked `full` (make test-full)
#   scripts/test.sh -k expr    pass a pytest -k filter (rostests are filtered by file name)
set -uo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# shellcheck disable=SC1091
source "$REPO/scripts/env.sh"
unset DISPLAY            # headless: GUI tests start their own Xvfb
export QT_QPA_PLATFORM=offscreen
exec /usr/bin/python3 "$REPO/scripts/run_tests.py" "$@"
