"""What the course's tools run with (demos, map making, the lab graders): processes stopped by
PID with their whole tree, a private roscore on a free port, a private Xvfb display and
screenshots, a Gazebo world rasterised into an occupancy grid; and the small shared helpers
(geometry, occupancy, transforms). Test-only helpers live in course_testing, which re-exports
these.

The names below are loaded on first use (PEP 562), so importing one small module such as
course_runtime.geometry (the simulator's yaw helper) does not load the process tools."""
import importlib

_WHERE = {
    'Proc': 'proc', 'start': 'proc', 'free_port': 'proc', 'wait_for': 'proc', 'run': 'proc',
    'stop_tree': 'proc', 'become_subreaper': 'proc', 'reap_orphans': 'proc',
    'RosCore': 'roscore',
    'SOFTWARE_GL': 'xvfb', 'Xvfb': 'xvfb', 'screenshot': 'xvfb',
}

__all__ = sorted(_WHERE)


def __getattr__(name):
    module = _WHERE.get(name)
    if module is None:
        raise AttributeError("module 'course_runtime' has no attribute %r" % name)
    value = getattr(importlib.import_module('course_runtime.' + module), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(list(globals()) + list(_WHERE))
