#!/usr/bin/env bash
# Build the course image from the repository's Dockerfile (runs scripts/setup.sh inside).
#   ./docker_build.bash            Debian 12 (bookworm) image, ros-course:bookworm
#   ./docker_build.bash trixie     Debian 13 (trixie) image, ros-course:trixie
# Behind a TLS-intercepting proxy (pip cannot reach PyPI inside the build), pass your CA
# bundle: COURSE_CA_BUNDLE=/etc/ssl/certs/ca-certificates.crt ./docker_build.bash
# (a BuildKit secret: used while building, never stored in the image).
set -euo pipefail
if [ $# -gt 0 ]; then export DEBIAN_RELEASE="$1"; shift; fi
source "$(dirname "${BASH_SOURCE[0]}")/common.bash"
secret=()
if [ -n "${COURSE_CA_BUNDLE:-}" ]; then
    [ -r "$COURSE_CA_BUNDLE" ] || { echo "docker_build.bash: COURSE_CA_BUNDLE=$COURSE_CA_BUNDLE: not a readable file" >&2; exit 2; }
    secret=(--secret "id=hostca,src=$COURSE_CA_BUNDLE")
fi
# BuildKit: the Dockerfile mounts build caches and the optional CA secret (RUN --mount)
DOCKER_BUILDKIT=1 docker build --progress=plain \
    --build-arg "DEBIAN_RELEASE=$DEBIAN_RELEASE" "${secret[@]}" "$@" \
    -t "$COURSE_IMAGE" -f "$REPO_DIR/Dockerfile" "$REPO_DIR"
next="./docker_run.bash"; [ "$DEBIAN_RELEASE" = bookworm ] || next="./docker_run.bash $DEBIAN_RELEASE"
echo "Built $COURSE_IMAGE. Next: xhost +local:root && $next"
