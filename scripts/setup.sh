#!/usr/bin/env bash
# One-command setup on Debian 12 (bookworm) or 13 (trixie): Debian packages, pinned PyPI
# packages (workspace-local), and the catkin workspace. Idempotent: a second run only rebuilds
# what changed. The Dockerfile runs exactly this script.
# deps/*.txt lines may start with `RELEASE:` (e.g. `trixie: pkg`): used on that release only.
#   scripts/setup.sh                 everything
#   scripts/setup.sh --debian-only   the Debian packages only (needs only scripts/ and deps/: the
#                                    Dockerfile's first layer, kept while deps/ does not change)
set -euo pipefail
DEBIAN_ONLY=""
case "${1:-}" in
    "") ;;
    --debian-only) DEBIAN_ONLY=1 ;;
    *) printf '[setup] ERROR: unknown option %s (usage: setup.sh [--debian-only])\n' "$1" >&2; exit 2 ;;
esac
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$REPO"
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:$PATH"

log() { printf '[setup] %s\n' "$*"; }
die() { printf '[setup] ERROR: %s\n' "$*" >&2; exit 1; }

SUDO=""
if [ "$(id -u)" != 0 ]; then
    command -v sudo >/dev/null || die "not root and no sudo: run as root to install packages"
    SUDO="sudo"
fi

# 0. Debian release ---------------------------------------------------------------------
SUPPORTED="bookworm trixie"
RELEASE=$(. /etc/os-release 2>/dev/null && echo "${VERSION_CODENAME:-}")
case " $SUPPORTED " in
    *" ${RELEASE:-?} "*) ;;
    *) die "unsupported system '$( . /etc/os-release 2>/dev/null; echo "${PRETTY_NAME:-unknown}")': supported are Debian 12 (bookworm) and Debian 13 (trixie)" ;;
esac
# deps file without comments and blanks, `RELEASE:` lines kept (prefix removed) on that release only
deps_for_release() {
    sed -e 's/#.*//' -e 's/^[[:space:]]*//' -e 's/[[:space:]]*$//' "$1" | grep -v '^$' \
        | awk -v r="$RELEASE" '/^[a-z]+:/ { sub(/:[[:space:]]*/, " "); if ($1 == r) print $2; next } { print }'
}

# 1. Debian packages -------------------------------------------------------------------
mapfile -t DEB_PKGS < <(deps_for_release deps/debian.txt | sed -e 's/[[:space:]]//g' -e '/^$/d')
missing=()
for p in "${DEB_PKGS[@]}"; do
    status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
    [ "$status" = "install ok installed" ] || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
    log "installing ${#missing[@]} Debian packages: ${missing[*]}"
    $SUDO apt-get update
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
else
    log "Debian packages: all ${#DEB_PKGS[@]} installed"
fi

# npm: Debian's package where nodejs is Debian's; a nodejs that bundles its own npm (NodeSource)
# conflicts with Debian's npm package, so it is only installed when no npm is on PATH
if ! command -v npm >/dev/null; then
    log "installing Debian's npm"
    $SUDO apt-get update
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends npm
fi
if [ -n "$DEBIAN_ONLY" ]; then
    log "done: Debian packages (--debian-only)"
    exit 0
fi

# 2. PyPI packages into a workspace-local directory ------------------------------------
PYDEPS="$REPO/.deps/python"
STAMP="$REPO/.deps/python.stamp"
reqs=$(deps_for_release deps/python.txt || true)
want=$(sha256sum deps/python.txt | cut -d' ' -f1)
have=$(cat "$STAMP" 2>/dev/null || true)
if [ "$want" != "$have" ]; then
    rm -rf "$PYDEPS"; mkdir -p "$PYDEPS"
    if [ -n "$reqs" ]; then
        if echo "$reqs" | grep -qv '=='; then die "deps/python.txt: every requirement must be pinned with =="; fi
        log "installing PyPI packages into .deps/python"
        /usr/bin/python3 -m pip install --disable-pip-version-check --no-warn-script-location \
            --no-deps --target "$PYDEPS" -r <(echo "$reqs")
    fi
    echo "$want" > "$STAMP"
else
    log "PyPI packages: up to date"
fi

# 3. JavaScript packages of the web view (pinned by course_web's package-lock.json) ------
bash "$REPO/catkin_ws/src/web/course_web/scripts/install_js.sh" || die "course_web's JavaScript packages could not be installed"

# 4. rosdep (textbook §1.6: rosdep update, rosdep install --from-paths src --ignore-src) -----
# Debian's python3-rosdep2 comes initialised, its 20-default.list naming the rosdistro
# repository on the internet. The course's rules are a local file (deps/rosdep/ros-course.yaml:
# Debian's package names for ROS libraries, [] for the workspace's own packages), listed first;
# the internet sources are set aside (Debian's file kept as 20-default.list.debian) and the
# rosdistro index is local too, so `rosdep update` works offline.
ROSDEP_LISTS=/etc/ros/rosdep/sources.list.d
put_file() {  # put_file PATH CONTENT: write only when it differs (idempotent)
    [ "$(cat "$1" 2>/dev/null)" = "$2" ] && return 0
    $SUDO mkdir -p "$(dirname "$1")"
    printf '%s\n' "$2" | $SUDO tee "$1" >/dev/null
    log "wrote $1"
}
command -v rosdep >/dev/null || die "no rosdep: python3-rosdep2 (deps/debian.txt) is not installed"
if [ -f "$ROSDEP_LISTS/20-default.list" ] && grep -q '^[^#]*https\?://' "$ROSDEP_LISTS/20-default.list" \
        && [ ! -f "$ROSDEP_LISTS/20-default.list.debian" ]; then
    $SUDO cp "$ROSDEP_LISTS/20-default.list" "$ROSDEP_LISTS/20-default.list.debian"
fi
put_file "$ROSDEP_LISTS/05-ros-course.list" "# the ROS course's rosdep rules (written by its scripts/setup.sh)
yaml file://$REPO/deps/rosdep/ros-course.yaml"
put_file "$ROSDEP_LISTS/20-default.list" "# rosdep's default sources, on this course machine local only (written by the course's
# scripts/setup.sh; Debian's list of internet sources is kept as 20-default.list.debian):
# 05-ros-course.list and Debian's 10-debian.list"
put_file /etc/xdg/rosdistro/config.yaml "# rosdistro index of the ROS course (written by its scripts/setup.sh)
index_url: file://$REPO/deps/rosdep/index-v4.yaml"
rosdep update >"$REPO/.deps/rosdep-update.log" 2>&1 || {
    cat "$REPO/.deps/rosdep-update.log" >&2
    die "rosdep update failed (log: .deps/rosdep-update.log)"
}
log "rosdep: course rules registered, cache updated"
# the book's `rosdep install --from-paths src --ignore-src -y` on the workspace: a no-op when
# deps/debian.txt already brought everything (Debian 12); installs what a rule names that the
# release does not pull in by itself. Not fatal: course_tasks/test_book_machine.py is the gate.
as_root=(); [ -z "$SUDO" ] && as_root=(--as-root apt:false)
if ! (cd "$REPO/catkin_ws" && rosdep install --from-paths src --ignore-src -y "${as_root[@]}" \
        >"$REPO/.deps/rosdep-install.log" 2>&1); then
    log "WARNING: rosdep install --from-paths src --ignore-src failed (log: .deps/rosdep-install.log): $(grep -m1 -iE 'error|cannot' "$REPO/.deps/rosdep-install.log")"
fi

# 5. catkin workspace ------------------------------------------------------------------
log "building catkin_ws with catkin_make"
mkdir -p "$REPO/.deps"
bash "$REPO/scripts/build.sh" all tests >"$REPO/.deps/catkin_make.log" 2>&1 || {
    tail -n 40 "$REPO/.deps/catkin_make.log" >&2
    die "catkin_make failed (full log: .deps/catkin_make.log)"
}
log "done: source scripts/env.sh to use the workspace"
