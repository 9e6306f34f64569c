# Entry points. `make test` and `make demo` run the (idempotent, fast when done) setup first.
SHELL := /bin/bash
.PHONY: setup build test test-full demo bench clean

setup:
	bash scripts/setup.sh

build:
	bash scripts/build.sh

test: setup
	bash scripts/test.sh

test-full: setup
	bash scripts/test.sh --full

demo: setup
	bash scripts/demo.sh

bench: setup
	bash scripts/bench.sh

clean:
	rm -rf catkin_ws/build catkin_ws/devel catkin_ws/src/CMakeLists.txt build
