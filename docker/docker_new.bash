#!/usr/bin/env bash
# A second terminal into the running course container (start it with ./docker_run.bash).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.bash"
if ! docker ps --format '{{.Names}}' | grep -qx "$COURSE_CONTAINER"; then
    echo "The container '$COURSE_CONTAINER' is not running: start it with ./docker_run.bash first." >&2
    exit 1
fi
exec docker exec -it "$COURSE_CONTAINER" bash -c 'source /course/scripts/env.sh; exec bash'
