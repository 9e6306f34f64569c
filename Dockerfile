# The course image: Debian 12 with its own ROS 1 packages and this repository built.
# Its only build step is scripts/setup.sh, the same script a host install runs, so the
# test suite (which runs setup.sh on a fresh machine) tests the image's steps too.
FROM debian:bookworm

ENV DEBIAN_FRONTEND=noninteractive \
    LANG=C.UTF-8 \
    LC_ALL=C.UTF-8

WORKDIR /course
COPY . /course
RUN bash /course/scripts/setup.sh \
 && echo 'source /course/scripts/env.sh' >> /root/.bashrc

# Student work lives in /root/workspace, mounted from the host by docker/docker_run.bash.
WORKDIR /root/workspace
CMD ["bash"]
