# Source this file (bash): `source scripts/env.sh`
# shellcheck shell=bash
# Puts Debian's /usr/bin first on PATH (ROS needs /usr/bin/python3, not a pyenv/venv python),
# adds the workspace-local PyPI packages and sources the catkin workspace.
_COURSE_REPO="$(cd "$(dirname "${BASH_SOURCE[0]:-$0}")/.." && pwd)"
export COURSE_REPO="$_COURSE_REPO"
PATH="/usr/bin:/bin:$(printf '%s' "$PATH" | tr ':' '\n' | grep -vxE '/usr/bin|/bin' | paste -sd: -)"
export PATH
case ":${PYTHONPATH:-}:" in
    *":$_COURSE_REPO/.deps/python:"*) ;;
    *) export PYTHONPATH="$_COURSE_REPO/.deps/python${PYTHONPATH:+:$PYTHONPATH}" ;;
esac
if [ -f "$_COURSE_REPO/catkin_ws/devel/setup.bash" ]; then
    # catkin's setup files read unset variables: allow that even under `set -u`
    case $- in *u*) _course_nounset=1; set +u ;; *) _course_nounset= ;; esac
    # shellcheck disable=SC1091
    source "$_COURSE_REPO/catkin_ws/devel/setup.bash"
    [ -n "$_course_nounset" ] && set -u
    unset _course_nounset
else
    echo "scripts/env.sh: catkin_ws is not built yet; run 'make setup' first" >&2
fi
unset _COURSE_REPO
