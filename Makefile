# Entry points. `make test` and `make demo` run the (idempotent, fast when done) setup first.
SHELL := /bin/bash
.PHONY: setup build test test-full test-stress test-class test-docker test-cold demo demo-lab2 bench clean
REPEAT ?= 1

setup:
	bash scripts/setup.sh

build:
	bash scripts/build.sh

test: setup
	bash scripts/test.sh

test-full: setup
	bash scripts/test.sh --full

# the suite with every core busy (stress-ng), REPEAT rounds: make test-stress REPEAT=3
test-stress: setup
	bash scripts/stress.sh --repeat $(REPEAT)

# grading a class: lab 1-3 rosters through labs/grade-class, locally and on a one-node Slurm,
# gradebooks compared (slow: tens of minutes; not part of make test)
test-class: setup
	bash labs/test-class.sh

# the course image in a real Docker engine (base image by mmdebstrap, no Docker Hub): build,
# course docker scripts with X11 on an Xvfb, make test inside: make test-docker RELEASE=trixie
RELEASE ?= bookworm
test-docker:
	bash scripts/test_docker.sh $(RELEASE)

# CI's run on a fresh machine, timed: a fresh clone of HEAD runs .ci/run (make test) in a
# container of the bare Debian base image, with no package, download or compiler cache
test-cold:
	COURSE_DOCKER_COLD=1 bash scripts/test_docker.sh $(RELEASE)

# the main demo: the space scanner maps the office, then navigates on its map;
# make demo web:=true also serves the course's web view (http://localhost:8080) for the demo
demo: setup
	bash scripts/demo.sh $(if $(filter true,$(web)),--web)

# the previous demo: the lab-2 reference graded on turtlesim
demo-lab2: setup
	bash scripts/demo_lab2.sh

bench: setup
	bash scripts/bench.sh

clean:
	rm -rf catkin_ws/build catkin_ws/devel catkin_ws/src/CMakeLists.txt build
