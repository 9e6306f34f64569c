#!/usr/bin/env bash
# A second terminal into the running course container (start it with ./docker_run.bash).
#   ./docker_new.bash            a shell;   ./docker_new.bash CMD...   run CMD there
set -euo pipefail
case "${1:-}" in bookworm|trixie) export DEBIAN_RELEASE="$1"; shift ;; esac
source "$(dirname "${BASH_SOURCE[0]}")/common.bash"
if ! docker ps --format '{{.Names}}' | grep -qx "$COURSE_CONTAINER"; then
    echo "The container '$COURSE_CONTAINER' is not running: start it with ./docker_run.bash first." >&2
    exit 1
fi
[ $# -gt 0 ] || set -- bash
exec docker exec "${DOCKER_TTY[@]}" "$COURSE_CONTAINER" bash -c 'source /course/scripts/env.sh; exec "$@"' bash "$@"
