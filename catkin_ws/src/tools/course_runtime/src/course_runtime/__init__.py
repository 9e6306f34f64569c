"""What the course's tools run with (demos, map making, the lab graders): processes stopped by
PID with their whole tree, a private roscore on a free port, a private Xvfb display and
screenshots, a Gazebo world rasterised into an occupancy grid. Test-only helpers live in
course_testing, which re-exports these."""
from course_runtime.proc import (Proc, start, free_port, wait_for, run, stop_tree, become_subreaper,
                                 reap_orphans)
from course_runtime.roscore import RosCore
from course_runtime.xvfb import SOFTWARE_GL, Xvfb, screenshot

__all__ = ['Proc', 'start', 'free_port', 'wait_for', 'run', 'stop_tree', 'become_subreaper',
           'reap_orphans', 'RosCore', 'SOFTWARE_GL', 'Xvfb', 'screenshot']
