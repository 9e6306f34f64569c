#!/usr/bin/env bash
# Start the course container with X11 forwarding (RViz, turtlesim, rqt_plot windows) and the
# host folder workspace/ mounted at /root/workspace. Everything else in the container is lost
# when this terminal closes: keep your catkin workspaces in /root/workspace.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.bash"
mkdir -p "$WORKSPACE_DIR"
gpu=(); [ -e /dev/dri ] && gpu=(--device /dev/dri:/dev/dri)   # Mesa GPU access when present
command -v xhost >/dev/null 2>&1 && xhost +local:root >/dev/null 2>&1 || true
exec docker run -it --rm \
    --name "$COURSE_CONTAINER" \
    --net=host \
    --env "DISPLAY=${DISPLAY:-:0}" \
    --env QT_X11_NO_MITSHM=1 \
    --volume /tmp/.X11-unix:/tmp/.X11-unix:rw \
    --volume "$WORKSPACE_DIR":/root/workspace:rw \
    "${gpu[@]}" \
    "$COURSE_IMAGE" bash
