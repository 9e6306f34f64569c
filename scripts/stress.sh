#!/usr/bin/env bash
# The test suite under full CPU load, repeated: scripts/stress.sh [--repeat N] [-k expr] [--full]
set -uo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# shellcheck disable=SC1091
source "$REPO/scripts/env.sh"
unset DISPLAY            # headless: GUI tests start their own Xvfb
export QT_QPA_PLATFORM=offscreen
exec /usr/bin/python3 "$REPO/scripts/stress.py" "$@"
