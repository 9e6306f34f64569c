# Shared settings of the course's docker scripts (sourced, not run).
# shellcheck shell=bash
# shellcheck disable=SC2034  # the variables are read by the scripts that source this file
# The image's Debian release: bookworm (Debian 12, the default) or trixie (Debian 13).
# Choose it with DEBIAN_RELEASE=trixie or as the scripts' first argument
# (./docker_build.bash trixie, ./docker_run.bash trixie, ./docker_new.bash trixie).
COURSE_RELEASES="bookworm trixie"
DEBIAN_RELEASE="${DEBIAN_RELEASE:-bookworm}"
case " $COURSE_RELEASES " in
    *" $DEBIAN_RELEASE "*) ;;
    *) echo "$(basename "$0"): unsupported Debian release '$DEBIAN_RELEASE' (supported: ${COURSE_RELEASES// /, })" >&2
       exit 2 ;;
esac
COURSE_IMAGE="${COURSE_IMAGE:-ros-course:$DEBIAN_RELEASE}"
COURSE_CONTAINER="${COURSE_CONTAINER:-ros-course}"
DOCKER_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO_DIR="$(cd "$DOCKER_DIR/.." && pwd)"
# The only folder that survives the container: create your catkin workspaces here.
WORKSPACE_DIR="${COURSE_WORKSPACE:-$REPO_DIR/workspace}"
# `docker run/exec -t` only when this terminal is one (scripts and tests pipe their input)
DOCKER_TTY=(-i)
if [ -t 0 ] && [ -t 1 ]; then DOCKER_TTY=(-it); fi
