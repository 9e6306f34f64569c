#!/usr/bin/env bash
# The course image in a real Docker engine (make test-docker RELEASE=bookworm|trixie; not part
# of make test):
#   1. installs docker.io and mmdebstrap when missing, starts dockerd when none runs (and stops
#      only the daemon it started);
#   2. makes the base image debian:RELEASE with mmdebstrap + docker import when it is missing
#      (Docker Hub is not needed; the image is kept as a cache);
#   3. builds the course image as a student does (docker/docker_build.bash RELEASE), passing
#      the host's CA bundle as a BuildKit secret (never stored in the image);
#   4. drives the course scripts: docker_run.bash with DISPLAY on an Xvfb screen of the host
#      (turtlesim and RViz windows must appear in a screenshot of that screen), docker_new.bash
#      into the running container, and a file written in /root/workspace must survive it;
#   5. runs `make test` inside a container of the image and prints its "N passed, N failed".
# Options (environment): COURSE_DOCKER_SUITE=0 skips step 5 (prints that it did);
# COURSE_DOCKER_REBUILD=0 uses an existing ros-course:RELEASE instead of building (step 3);
# COURSE_DOCKER_COLD=1 replaces steps 3-5 by CI's run on a fresh machine (make test-cold): a
# container of the bare base image clones the repository's HEAD and runs .ci/run (make test:
# setup.sh, then the suite) with nothing cached - Debian packages downloaded, PyPI and npm
# packages fetched, every C++ file compiled by an empty ccache - and prints the time it took;
# COURSE_CA_BUNDLE (default: /etc/ssl/certs/ca-certificates.crt when present).
# Figures and logs: build/test-docker/RELEASE/ (screenshot.png, build.log, suite.log, cold.log).
# shellcheck disable=SC2317  # cleanup and the check functions are called through trap and check
set -uo pipefail
REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export PATH="/usr/bin:/bin:/usr/sbin:/sbin:$PATH"   # Debian's docker client (20.10 talks BuildKit)
RELEASE="${1:-${RELEASE:-bookworm}}"
case "$RELEASE" in
    bookworm|trixie) ;;
    *) echo "test_docker.sh: unsupported release '$RELEASE' (supported: bookworm, trixie)" >&2; exit 2 ;;
esac
OUT="$REPO/build/test-docker/$RELEASE"
mkdir -p "$OUT"
log() { printf '[test-docker %s] %s\n' "$RELEASE" "$*"; }
die() { printf '[test-docker %s] ERROR: %s\n' "$RELEASE" "$*" >&2; exit 1; }
now() { date +%s; }

# ---- cleanup: only what this script started ----------------------------------------------
DOCKERD_PID=""; XVFB_PID=""; RUN_PID=""; CONTAINERS=()
cleanup() {
    for c in "${CONTAINERS[@]}"; do docker rm -f "$c" >/dev/null 2>&1 || true; done
    [ -n "$RUN_PID" ] && kill "$RUN_PID" 2>/dev/null
    [ -n "$XVFB_PID" ] && kill "$XVFB_PID" 2>/dev/null && wait "$XVFB_PID" 2>/dev/null
    if [ -n "$DOCKERD_PID" ]; then
        log "stopping the dockerd this script started (pid $DOCKERD_PID)"
        kill "$DOCKERD_PID" 2>/dev/null
        for _ in $(seq 60); do kill -0 "$DOCKERD_PID" 2>/dev/null || break; sleep 0.5; done
    fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM

# ---- 1. tools and daemon -------------------------------------------------------------------
need=()
for p in docker.io mmdebstrap xvfb imagemagick x11-utils python3-pil python3-numpy; do
    [ "$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null)" = "install ok installed" ] || need+=("$p")
done
if [ ${#need[@]} -gt 0 ]; then
    log "installing ${need[*]}"
    apt-get -o DPkg::Lock::Timeout=600 install -y --no-install-recommends "${need[@]}" >"$OUT/apt.log" 2>&1 \
        || { apt-get update >>"$OUT/apt.log" 2>&1; apt-get -o DPkg::Lock::Timeout=600 install -y --no-install-recommends "${need[@]}" >>"$OUT/apt.log" 2>&1; } \
        || die "could not install ${need[*]} (see $OUT/apt.log)"
fi
if ! docker info >/dev/null 2>&1; then
    log "no Docker daemon runs: starting dockerd"
    dockerd >"$OUT/dockerd.log" 2>&1 &
    DOCKERD_PID=$!
    for _ in $(seq 120); do docker info >/dev/null 2>&1 && break; sleep 0.5; done
    docker info >/dev/null 2>&1 || die "dockerd did not come up in 60 s (see $OUT/dockerd.log)"
fi
CA="${COURSE_CA_BUNDLE:-}"
[ -z "$CA" ] && [ -r /etc/ssl/certs/ca-certificates.crt ] && CA=/etc/ssl/certs/ca-certificates.crt
export COURSE_CA_BUNDLE="$CA"
ca_args=()      # a container's PyPI and npm downloads trust the host's CA bundle
[ -n "$CA" ] && ca_args=(--volume "$CA:/run/host-ca.pem:ro" --env PIP_CERT=/run/host-ca.pem
                         --env SSL_CERT_FILE=/run/host-ca.pem --env REQUESTS_CA_BUNDLE=/run/host-ca.pem
                         --env NODE_EXTRA_CA_CERTS=/run/host-ca.pem)
# the suite tests the lab graders' bubblewrap sandbox, which (as root) makes mount, PID and
# network namespaces and tmpfs mounts as on a host: SYS_ADMIN/NET_ADMIN, no seccomp filter
# (--privileged is refused on machines that do not grant every capability)
suite_args=(--cap-add SYS_ADMIN --cap-add NET_ADMIN --security-opt seccomp=unconfined
            --security-opt apparmor=unconfined --shm-size=1g "${ca_args[@]}")

# ---- 2. base image --------------------------------------------------------------------------
BASE_S="cached"
if ! docker image inspect "debian:$RELEASE" >/dev/null 2>&1; then
    log "making debian:$RELEASE with mmdebstrap (minbase) + docker import"
    t0=$(now)
    mirror=http://deb.debian.org/debian
    # like Docker Hub's debian images: dpkg without fsync (force-unsafe-io), no translations
    mmdebstrap --variant=minbase --dpkgopt=force-unsafe-io --aptopt='Acquire::Languages "none"' "$RELEASE" - \
        "deb $mirror $RELEASE main" "deb $mirror $RELEASE-updates main" \
        "deb http://deb.debian.org/debian-security $RELEASE-security main" 2>"$OUT/mmdebstrap.log" \
        | docker import --change 'CMD ["bash"]' - "debian:$RELEASE" >/dev/null \
        || { docker rmi "debian:$RELEASE" >/dev/null 2>&1; die "base image failed (see $OUT/mmdebstrap.log)"; }
    BASE_S="$(( $(now) - t0 )) s"
fi
log "base image debian:$RELEASE: $BASE_S"

# ---- cold: CI on a fresh machine (COURSE_DOCKER_COLD=1, make test-cold) ---------------------
suite_line() {  # suite_line LOG: the log's closing "N passed, N failed" line
    grep -E '^([A-Za-z]+: )?[0-9]+ passed, [0-9]+ failed' "$1" | tail -n 1
}
if [ "${COURSE_DOCKER_COLD:-0}" = 1 ]; then
    CNAME="ros-course-cold-$RELEASE-$$"
    CONTAINERS+=("$CNAME")
    log "make test from a cold cache: a fresh clone of HEAD in a container of debian:$RELEASE (log: $OUT/cold.log)"
    t0=$(now)
    # git, make and the CA certificates are what a CI machine has before it clones
    docker run --rm --name "$CNAME" "${suite_args[@]}" --volume "$REPO:/src:ro" "debian:$RELEASE" \
        bash -c 'set -e
                 apt-get update -qq && apt-get install -y -qq --no-install-recommends git make ca-certificates >/dev/null
                 git clone -q --no-hardlinks /src /course && cd /course && git log --oneline -1
                 s=$(date +%s); CI=true bash .ci/run; echo "[cold] make test took $(( $(date +%s) - s )) s"' \
        </dev/null >"$OUT/cold.log" 2>&1
    COLD_RC=$?
    COLD_S=$(( $(now) - t0 ))
    LINE=$(suite_line "$OUT/cold.log")
    [ -n "$LINE" ] || { LINE="0 passed, 1 failed"; tail -n 30 "$OUT/cold.log"; }
    grep -E '^(FAILED|ERROR)' "$OUT/cold.log" | head -n 40
    MAKE_S=$(sed -n 's/^\[cold\] make test took \([0-9]*\) s$/\1/p' "$OUT/cold.log")
    SUITE_S=$(sed -n 's/^=== summary (\([0-9]*\) s.*/\1/p' "$OUT/cold.log")
    log "figures: make test from a cold cache ${MAKE_S:-?} s (setup $(( ${MAKE_S:-0} - ${SUITE_S:-0} )) s, suite ${SUITE_S:-?} s), container in all ${COLD_S} s: $LINE"
    echo "$LINE"
    [ "$COLD_RC" = 0 ] && ! grep -qE ' [1-9][0-9]* failed' <<<"$LINE"
    exit $?
fi

# ---- 3. the course image, built as a student builds it --------------------------------------
IMAGE="ros-course:$RELEASE"
t0=$(now)
if [ "${COURSE_DOCKER_REBUILD:-1}" = 0 ] && docker image inspect "$IMAGE" >/dev/null 2>&1; then
    log "COURSE_DOCKER_REBUILD=0: using the existing $IMAGE (built $(docker image inspect -f '{{.Created}}' "$IMAGE"))"
    BUILD_S="(not rebuilt) 0"
else
    log "building $IMAGE with docker/docker_build.bash $RELEASE (log: $OUT/build.log)"
    COURSE_IMAGE="$IMAGE" bash "$REPO/docker/docker_build.bash" "$RELEASE" >"$OUT/build.log" 2>&1 \
        || { tail -n 40 "$OUT/build.log" >&2; die "docker_build.bash $RELEASE failed (see $OUT/build.log)"; }
    BUILD_S=$(( $(now) - t0 ))
fi
SIZE=$(docker image inspect -f '{{.Size}}' "$IMAGE" | awk '{printf "%.2f GB", $1/1e9}')
log "image $IMAGE built in $BUILD_S s (all steps cached when nothing changed), size $SIZE"
if grep -rqs "BEGIN CERTIFICATE" <(docker run --rm "$IMAGE" bash -c 'ls /run/secrets 2>/dev/null; cat /run/secrets/* 2>/dev/null'); then
    die "the CA secret is in the image"
fi

# ---- 4. the course scripts, as a student uses them -------------------------------------------
CHECK_PASS=0; CHECK_FAIL=0
check() {  # check NAME CMD...: one course-script check
    local name="$1"; shift
    if "$@"; then CHECK_PASS=$((CHECK_PASS + 1)); log "ok: $name"
    else CHECK_FAIL=$((CHECK_FAIL + 1)); log "FAILED: $name"; fi
}
for n in $(seq 140 199); do
    [ -e "/tmp/.X11-unix/X$n" ] || [ -e "/tmp/.X$n-lock" ] || break
done
DISP=":$n"
Xvfb "$DISP" -screen 0 1600x1000x24 -nolisten tcp >"$OUT/xvfb.log" 2>&1 &
XVFB_PID=$!
for _ in $(seq 100); do [ -e "/tmp/.X11-unix/X$n" ] && break; sleep 0.1; done
[ -e "/tmp/.X11-unix/X$n" ] || die "Xvfb $DISP did not start (see $OUT/xvfb.log)"
PORT=$(/usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("",0)); print(s.getsockname()[1])')
WS=$(mktemp -d "$OUT/workspace.XXXX")
NAME="ros-course-test-$RELEASE-$$"
CONTAINERS+=("$NAME")
export DISPLAY="$DISP" COURSE_IMAGE="$IMAGE" COURSE_CONTAINER="$NAME" COURSE_WORKSPACE="$WS"
STAMP="written in the container $(date +%s%N)"
# --net=host (docker_run.bash): the container's roscore on a free port of the host's
bash "$REPO/docker/docker_run.bash" "$RELEASE" bash -c "
    export ROS_MASTER_URI=http://localhost:$PORT
    roscore -p $PORT >/tmp/roscore.log 2>&1 &
    until rostopic list >/dev/null 2>&1; do sleep 0.5; done
    rviz >/tmp/rviz.log 2>&1 &
    echo '$STAMP' > /root/workspace/from_container.txt
    sleep infinity" </dev/null >"$OUT/run.log" 2>&1 &
RUN_PID=$!

windows_up() {   # both windows mapped on the host's screen, and their pixels in a screenshot
    # Xvfb has no window manager: windows open at the top left, the last one on top. RViz comes
    # first; once its window is up, turtlesim (500x500) opens over its corner through a second
    # terminal (docker_new.bash), so that both backgrounds are visible.
    local deadline=$(( $(now) + 180 )) turtle_started=""
    while [ "$(now)" -lt "$deadline" ]; do
        kill -0 "$RUN_PID" 2>/dev/null || { log "docker_run.bash exited: $(tail -n 5 "$OUT/run.log")"; return 1; }
        tree=$(DISPLAY="$DISP" xwininfo -root -tree 2>/dev/null)
        if [ -z "$turtle_started" ] && grep -q 'RViz' <<<"$tree"; then
            bash "$REPO/docker/docker_new.bash" "$RELEASE" bash -c \
                "ROS_MASTER_URI=http://localhost:$PORT rosrun turtlesim turtlesim_node >/tmp/turtlesim.log 2>&1" \
                </dev/null >>"$OUT/run.log" 2>&1 &
            turtle_started=1
        fi
        if grep -q '"TurtleSim"' <<<"$tree" && grep -q 'RViz' <<<"$tree"; then
            sleep 8        # let RViz draw its first frames
            import -display "$DISP" -window root "$OUT/screenshot.png" 2>/dev/null || return 1
            /usr/bin/python3 - "$OUT/screenshot.png" <<'EOF' && return 0
import sys
import numpy as np
from PIL import Image
rgb = np.asarray(Image.open(sys.argv[1]).convert('RGB')).astype(int)
def count(c):
    return int(np.all(np.abs(rgb - np.array(c)) <= 2, axis=2).sum())
turtle, rviz = count((69, 86, 255)), count((48, 48, 48))   # turtlesim / RViz backgrounds
print('[screenshot] turtlesim background px: %d, RViz 3D view background px: %d' % (turtle, rviz))
sys.exit(0 if turtle > 100000 and rviz > 50000 else 1)
EOF
        fi
        sleep 2
    done
    log "windows not seen in 180 s; X windows: $(grep -o '"[^"]*"' <<<"$tree" | sort -u | tr '\n' ' ')"
    log "container log: $(docker exec "$NAME" bash -c 'tail -n 5 /tmp/rviz.log /tmp/turtlesim.log' 2>&1)"
    return 1
}
check "docker_run.bash: turtlesim and RViz windows on the host's screen ($OUT/screenshot.png)" windows_up
new_sees_turtle() {
    out=$(bash "$REPO/docker/docker_new.bash" "$RELEASE" bash -c "ROS_MASTER_URI=http://localhost:$PORT rostopic list" </dev/null 2>&1)
    grep -qx /turtle1/pose <<<"$out" || { log "docker_new.bash rostopic list: $out"; return 1; }
}
check "docker_new.bash: a second terminal into the running container sees /turtle1/pose" new_sees_turtle
docker rm -f "$NAME" >/dev/null 2>&1
wait "$RUN_PID" 2>/dev/null; RUN_PID=""
survives() {
    [ "$(cat "$WS/from_container.txt" 2>/dev/null)" = "$STAMP" ] || { log "no $WS/from_container.txt after the container"; return 1; }
    out=$(bash "$REPO/docker/docker_run.bash" "$RELEASE" cat /root/workspace/from_container.txt </dev/null 2>&1)
    [ "$out" = "$STAMP" ] || { log "a new container reads: $out"; return 1; }
}
check "/root/workspace survives the container (host folder, and a new container reads it)" survives
kill "$XVFB_PID" 2>/dev/null; wait "$XVFB_PID" 2>/dev/null; XVFB_PID=""
unset DISPLAY
log "course scripts: $CHECK_PASS passed, $CHECK_FAIL failed"

# ---- 5. the test suite inside a container -----------------------------------------------------
SUITE_LINE="suite not run (COURSE_DOCKER_SUITE=0)"; SUITE_S=0; SUITE_RC=0
if [ "${COURSE_DOCKER_SUITE:-1}" != 0 ]; then
    SNAME="ros-course-suite-$RELEASE-$$"
    CONTAINERS+=("$SNAME")
    log "make test in a container of $IMAGE (log: $OUT/suite.log)"
    t0=$(now)
    # a named volume keeps the container's ccache between runs of this script (as a CI machine
    # keeps its own; make test-cold measures the run without it)
    docker run --rm --name "$SNAME" "${suite_args[@]}" \
        --volume "ros-course-ccache-$RELEASE:/root/.cache/ccache" "$IMAGE" \
        bash -c 'cd /course && make test' </dev/null >"$OUT/suite.log" 2>&1
    SUITE_RC=$?
    SUITE_S=$(( $(now) - t0 ))
    SUITE_LINE=$(suite_line "$OUT/suite.log")
    [ -n "$SUITE_LINE" ] || { SUITE_LINE="0 passed, 1 failed"; tail -n 30 "$OUT/suite.log"; }
    grep -E '^(FAILED|ERROR)|^\[run_tests\].*(FAIL|fail)' "$OUT/suite.log" | head -n 40
fi

log "figures: base image $BASE_S; image build ${BUILD_S} s, size $SIZE; course scripts $CHECK_PASS passed, $CHECK_FAIL failed; suite ${SUITE_S} s: $SUITE_LINE"
[ "$CHECK_FAIL" = 0 ] && [ "$SUITE_RC" = 0 ] && ! grep -qE ' [1-9][0-9]* failed' <<<"$SUITE_LINE"
rc=$?
echo "$SUITE_LINE" | grep -qE '^([A-Za-z]+: )?[0-9]+ passed' && echo "$SUITE_LINE"
exit $rc
