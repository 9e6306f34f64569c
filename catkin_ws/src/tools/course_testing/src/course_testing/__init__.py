"""Helpers for tests and graders: processes, a private roscore, Xvfb and screenshots."""
from course_testing.proc import (Proc, start, free_port, wait_for, run, stop_tree, become_subreaper,
                                   reap_orphans)
from course_testing.load import CpuLoad, cpu_load
from course_testing.roscore import RosCore
from course_testing.xvfb import SOFTWARE_GL, Xvfb, screenshot

__all__ = ['Proc', 'start', 'free_port', 'wait_for', 'run', 'stop_tree', 'become_subreaper',
           'reap_orphans', 'CpuLoad', 'cpu_load', 'RosCore', 'SOFTWARE_GL', 'Xvfb', 'screenshot']
