#!/usr/bin/env bash
# make demo-lab2: the lab-2 reference solution (ISU 123451, variant 1) graded on turtlesim.
# Runs headless on a master of its own (rostest picks a free port); with DISPLAY set the two
# turtlesim windows appear. Prints the measured time, the points turtle 1 visited (closest
# distance, time) and how far turtle 2's path deviates, all measured by the lab-2 grader.
set -uo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# shellcheck disable=SC1091
source "$REPO/scripts/env.sh"
ISU="${ISU:-123451}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
echo "[demo] lab 2 reference, ISU $ISU: two turtlesims in /ns1_$ISU and /ns2_$ISU${DISPLAY:+ (windows on $DISPLAY)}"
"$REPO/labs/grade" lab2 --isu "$ISU" --repo "$REPO/labs/lab2/reference" --junit "$out/report.xml"
rc=$?
[ "$rc" = 0 ] && echo "[demo] done: every lab-2 criterion passed" || echo "[demo] FAILED (exit $rc)"
exit "$rc"
