# The course image: Debian (12 bookworm or 13 trixie) with its own ROS 1 packages and this
# repository built. Its only build steps are scripts/setup.sh, the same script a host install
# runs, so the test suite (which runs setup.sh on a fresh machine) tests the image's steps too.
#
#   DOCKER_BUILDKIT=1 docker build --build-arg DEBIAN_RELEASE=trixie -t ros-course:trixie .
#
# BuildKit is needed (docker/docker_build.bash sets DOCKER_BUILDKIT=1): the RUN below mounts
# build caches (ccache, downloaded .deb files: fast rebuilds, not in the image) and,
# optionally, a CA bundle. ROS_PARALLEL_JOBS: catkin_make's default adds `-l<cores>`, which on a
# busy machine builds one file at a time. No `# syntax=` line on purpose: the
# Dockerfile frontend built into Docker >= 20.10 reads RUN --mount, and naming a frontend
# image would make every build pull it from Docker Hub.
#
# Behind a TLS-intercepting proxy, pass the host's CA bundle as a build secret:
#   --secret id=hostca,src=/etc/ssl/certs/ca-certificates.crt
# PyPI and npm downloads in setup.sh trust it during that RUN only; it never lands in a layer
# of the image.
ARG DEBIAN_RELEASE=bookworm
FROM debian:${DEBIAN_RELEASE}
ARG DEBIAN_RELEASE

ENV DEBIAN_FRONTEND=noninteractive \
    LANG=C.UTF-8 \
    LC_ALL=C.UTF-8

WORKDIR /course
# Two layers, both scripts/setup.sh: the Debian packages first (from setup.sh and deps/ alone,
# so a rebuild after a change of the code reuses them), then the rest of setup.sh on the whole
# repository (PyPI and npm packages, catkin_make with the ccache kept between builds).
COPY scripts/setup.sh /course/scripts/setup.sh
COPY deps/ /course/deps/
RUN --mount=type=cache,target=/var/cache/apt,sharing=private \
    bash /course/scripts/setup.sh --debian-only
COPY . /course
RUN --mount=type=secret,id=hostca \
    --mount=type=cache,target=/var/cache/course-ccache \
    export CCACHE_DIR=/var/cache/course-ccache ROS_PARALLEL_JOBS="-j$(nproc)" PIP_NO_CACHE_DIR=1 \
 && if [ -s /run/secrets/hostca ]; then \
        export PIP_CERT=/run/secrets/hostca SSL_CERT_FILE=/run/secrets/hostca \
               REQUESTS_CA_BUNDLE=/run/secrets/hostca NODE_EXTRA_CA_CERTS=/run/secrets/hostca; \
    fi \
 && bash /course/scripts/setup.sh \
 && echo 'source /course/scripts/env.sh' >> /root/.bashrc

# Student work lives in /root/workspace, mounted from the host by docker/docker_run.bash.
WORKDIR /root/workspace
CMD ["bash"]
