#!/usr/bin/env bash
# make demo: the project's main demo. The space scanner maps the office on its own (gmapping +
# move_base + frontier exploration), saves the map (PGM + YAML + a PNG of the driven path),
# restarts on it with AMCL + move_base, drives to a goal in every room and prints a summary
# (map quality, ATE, goals reached, times). Headless on a master of its own; with DISPLAY set,
# RViz shows each phase. Output in build/demo/. Options: see `rosrun space_scanner_bringup demo -h`.
set -uo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# shellcheck disable=SC1091
source "$REPO/scripts/env.sh"
cd "$REPO" || exit 1
exec rosrun space_scanner_bringup demo --out "$REPO/build/demo" "$@"
