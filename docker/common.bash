# Shared settings of the course's docker scripts (sourced, not run).
COURSE_IMAGE="${COURSE_IMAGE:-ros-course:bookworm}"
COURSE_CONTAINER="${COURSE_CONTAINER:-ros-course}"
DOCKER_DIR="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO_DIR="$(cd "$DOCKER_DIR/.." && pwd)"
# The only folder that survives the container: create your catkin workspaces here.
WORKSPACE_DIR="${COURSE_WORKSPACE:-$REPO_DIR/workspace}"
