#!/usr/bin/env bash
# Install the Docker engine on a Debian/Ubuntu host and let the current user run it.
set -euo pipefail
if command -v docker >/dev/null 2>&1 && docker info >/dev/null 2>&1; then
    echo "Docker is already installed and running."
    exit 0
fi
SUDO=""; [ "$(id -u)" = 0 ] || SUDO="sudo"
$SUDO apt-get update
$SUDO apt-get install -y docker.io x11-xserver-utils
$SUDO systemctl enable --now docker 2>/dev/null || $SUDO service docker start || true
if [ "$(id -u)" != 0 ]; then
    $SUDO usermod -aG docker "$USER"
    echo "Added $USER to the docker group: log out and back in (or run 'newgrp docker')."
fi
echo "Docker installed. Next: ./docker_build.bash"
