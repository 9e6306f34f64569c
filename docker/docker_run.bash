#!/usr/bin/env bash
# Start the course container with X11 forwarding (RViz, turtlesim, rqt_plot windows) and the
# host folder workspace/ mounted at /root/workspace. Everything else in the container is lost
# when this terminal closes: keep your catkin workspaces in /root/workspace. With --net=host
# the course web view (roslaunch course_web web.launch, bound to 127.0.0.1) opens in the host's
# browser at the URL it prints (http://localhost:8080/?token=...); nothing else is needed, and
# address:=0.0.0.0 would open it to the other machines of the network (still with the token).
#   ./docker_run.bash                  a shell in the Debian 12 (bookworm) image
#   ./docker_run.bash trixie           a shell in the Debian 13 (trixie) image
#   ./docker_run.bash [trixie] CMD...  run CMD (in the course's ROS environment) instead
set -euo pipefail
case "${1:-}" in bookworm|trixie) export DEBIAN_RELEASE="$1"; shift ;; esac
source "$(dirname "${BASH_SOURCE[0]}")/common.bash"
mkdir -p "$WORKSPACE_DIR"
gpu=(); [ -e /dev/dri ] && gpu=(--device /dev/dri:/dev/dri)   # Mesa GPU access when present
if command -v xhost >/dev/null 2>&1; then xhost +local:root >/dev/null 2>&1 || true; fi
cmd=(bash); [ $# -gt 0 ] && cmd=(bash -c 'source /course/scripts/env.sh && exec "$@"' bash "$@")
exec docker run "${DOCKER_TTY[@]}" --rm \
    --name "$COURSE_CONTAINER" \
    --net=host \
    --env "DISPLAY=${DISPLAY:-:0}" \
    --env QT_X11_NO_MITSHM=1 \
    --volume /tmp/.X11-unix:/tmp/.X11-unix:rw \
    --volume "$WORKSPACE_DIR":/root/workspace:rw \
    "${gpu[@]}" \
    "$COURSE_IMAGE" "${cmd[@]}"
