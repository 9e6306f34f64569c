#!/usr/bin/env bash
# Rebuild the catkin workspace (after `make setup` installed the dependencies).
set -euo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PATH="/usr/bin:/bin:$PATH"
cd "$REPO/catkin_ws"
mkdir -p "$REPO/.deps"
exec 9>"$REPO/.deps/build.lock"; flock 9     # one catkin_make at a time in this workspace
catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release "$@"
