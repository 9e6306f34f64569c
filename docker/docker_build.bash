#!/usr/bin/env bash
# Build the course image from the repository's Dockerfile (runs scripts/setup.sh inside).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.bash"
docker build -t "$COURSE_IMAGE" -f "$REPO_DIR/Dockerfile" "$REPO_DIR"
echo "Built $COURSE_IMAGE. Next: xhost +local:root && ./docker_run.bash"
