"""RosServices.wait: the timeout, and waiting past it while sim time has not started (rospy faked)."""
import threading

import pytest
import rospy   # Debian's python3-rospy: missing = a broken install, a failure

from controller_manager import ros_spawner


class FakeRospy(object):
    """The rospy functions RosServices.wait uses; services appear after ``available_after`` tries."""
    ROSException = rospy.ROSException

    def __init__(self, available_after, sim_time, clock_after):
        self.tries = 0
        self.available_after = available_after
        self.sim_time = sim_time
        self.clock_after = clock_after
        self.log = []

    def wait_for_service(self, name, timeout):
        self.tries += 1
        if self.tries <= self.available_after:
            raise rospy.ROSException('timeout exceeded while waiting for service %s' % name)

    def get_param(self, name, default=None):
        assert name == '/use_sim_time'
        return self.sim_time

    def get_rostime(self):
        return rospy.Time(0 if self.tries <= self.clock_after else 5)

    def is_shutdown(self):
        return False

    def loginfo(self, msg):
        self.log.append(msg)

    def loginfo_throttle(self, period, msg):
        self.log.append(msg)


class FakeClock(object):
    """time.monotonic that advances 1 s per call."""

    def __init__(self):
        self.t = 0.0

    def monotonic(self):
        self.t += 1.0
        return self.t


@pytest.fixture
def services(monkeypatch):
    def make(available_after, sim_time=False, clock_after=0):
        fake = FakeRospy(available_after, sim_time, clock_after)
        monkeypatch.setattr(ros_spawner, 'rospy', fake)
        monkeypatch.setattr(ros_spawner, 'time', FakeClock())
        s = ros_spawner.RosServices.__new__(ros_spawner.RosServices)
        s.names = {'load_controller': 'cm/load_controller', 'switch_controller': 'cm/switch_controller',
                   'unload_controller': 'cm/unload_controller'}
        return s, fake
    return make


def test_services_present(services):
    s, fake = services(0)
    assert s.wait(30.0, threading.Event())
    assert fake.tries == 3


def test_timeout_without_sim_time(services):
    s, fake = services(available_after=1000)
    assert not s.wait(5.0, threading.Event())
    assert fake.tries < 10


def test_no_timeout_waits_until_available(services):
    s, fake = services(available_after=50)
    assert s.wait(0.0, threading.Event())


def test_waits_past_timeout_until_the_clock_starts(services):
    s, fake = services(available_after=32, sim_time=True, clock_after=30)
    assert s.wait(5.0, threading.Event())   # the clock started at try 31, services at 33
    assert any('no /clock has been received yet' in m for m in fake.log)


def test_gives_up_after_clock_started(services):
    s, fake = services(available_after=1000, sim_time=True, clock_after=20)
    assert not s.wait(5.0, threading.Event())
    assert 20 < fake.tries < 30   # a full timeout after the clock started, not more


def test_stop_event(services):
    s, fake = services(available_after=1000)
    ev = threading.Event()
    ev.set()
    assert not s.wait(0.0, ev)
