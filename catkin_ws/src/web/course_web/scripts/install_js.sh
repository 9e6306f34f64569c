#!/usr/bin/env bash
# Installs course_web's JavaScript dependencies (pinned in package-lock.json) from the npm
# registry and copies the files the page loads into www/vendor, so that the page works
# without internet. Idempotent: does nothing when www/vendor matches the lock file.
# The first run needs the npm registry; later runs (`npm ci --offline`) use npm's cache.
set -euo pipefail
PKG="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$PKG"
log() { printf '[course_web] %s\n' "$*"; }
die() { printf '[course_web] ERROR: %s\n' "$*" >&2; exit 1; }

command -v npm >/dev/null || die "npm not found: install Debian's nodejs and npm (deps/debian.txt)"
VENDOR="$PKG/www/vendor"
STAMP="$VENDOR/.stamp"
want=$(cat package-lock.json "${BASH_SOURCE[0]}" | sha256sum | cut -d' ' -f1)
if [ "${1:-}" != "--force" ] && [ -f "$STAMP" ] && [ "$(cat "$STAMP")" = "$want" ]; then
    log "JavaScript dependencies: up to date (www/vendor)"
    exit 0
fi

log "npm ci (pinned by package-lock.json)"
if ! npm ci --offline --ignore-scripts --no-audit --no-fund >/dev/null 2>&1; then
    npm ci --ignore-scripts --no-audit --no-fund >/dev/null || die "npm ci failed (is the npm registry reachable?)"
fi

rm -rf "$VENDOR"
mkdir -p "$VENDOR/three/addons/controls" "$VENDOR/three/addons/loaders"
NM="$PKG/node_modules"
cp "$NM/roslib/build/roslib.min.js" "$VENDOR/roslib.min.js"
cp "$NM/three/build/three.module.min.js" "$VENDOR/three/three.module.js"
cp "$NM/three/examples/jsm/controls/OrbitControls.js" "$VENDOR/three/addons/controls/"
for f in STLLoader ColladaLoader TGALoader; do
    cp "$NM/three/examples/jsm/loaders/$f.js" "$VENDOR/three/addons/loaders/"
done
cp "$NM/roslib/LICENSE" "$VENDOR/LICENSE.roslib" 2>/dev/null || true
cp "$NM/three/LICENSE" "$VENDOR/LICENSE.three"
echo "$want" > "$STAMP"
log "vendored roslib $(node -p 'require("./node_modules/roslib/package.json").version') and three $(node -p 'require("./node_modules/three/package.json").version') into www/vendor"
