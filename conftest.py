"""Shared pytest fixtures: a private roscore, an Xvfb display, a scratch ROS log dir."""
import os

import pytest

REPO = os.path.dirname(os.path.abspath(__file__))


@pytest.fixture
def repo():
    return REPO


@pytest.fixture
def roscore(tmp_path):
    """A roscore of this test's own on a free port; `.env` points child processes at it."""
    from course_testing import RosCore
    core = RosCore(log_dir=str(tmp_path / 'ros_log'))
    core.start()
    try:
        yield core
    finally:
        core.stop()


@pytest.fixture
def xvfb():
    """An Xvfb display of this test's own; `.env` has DISPLAY set, `.display` is ':N'."""
    from course_testing import Xvfb
    x = Xvfb()
    x.start()
    try:
        yield x
    finally:
        x.stop()


@pytest.fixture
def screen():
    """A 1600x1000 Xvfb display of this test's own: room for RViz's main window."""
    from course_testing import Xvfb
    x = Xvfb(1600, 1000)
    x.start()
    try:
        yield x
    finally:
        x.stop()


@pytest.fixture
def rviz_env(roscore, screen):
    """Environment for GUI programs (RViz, Qt windows) on the private `screen` talking to the
    private `roscore`: the test runner's QT_QPA_PLATFORM=offscreen (scripts/test.sh, for
    in-process Qt) is removed, or RViz cannot create its render window."""
    env = dict(roscore.env, DISPLAY=screen.display)
    env.pop('QT_QPA_PLATFORM', None)
    return env
