"""Helpers for tests: processes, a private roscore, Xvfb and screenshots (from course_runtime,
which the course's tools run with), CPU load, RViz screenshot checks, simulation probes."""
from course_runtime import world_map  # noqa: F401  (from course_testing import world_map)
from course_runtime.proc import (Proc, start, free_port, wait_for, run, stop_tree, become_subreaper,
                                 reap_orphans)
from course_runtime.roscore import RosCore
from course_runtime.xvfb import SOFTWARE_GL, Xvfb, screenshot
from course_testing.load import CpuLoad, cpu_load

__all__ = ['Proc', 'start', 'free_port', 'wait_for', 'run', 'stop_tree', 'become_subreaper',
           'reap_orphans', 'CpuLoad', 'cpu_load', 'RosCore', 'SOFTWARE_GL', 'Xvfb', 'screenshot',
           'world_map']
