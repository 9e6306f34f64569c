"""Helpers of the controller_manager_tests rostest nodes: service proxies, waits, /rosout."""
import threading
import time

import rospy
from controller_manager_msgs.srv import (ListControllers, ListControllerTypes, LoadController,
                                         ReloadControllerLibraries, SwitchController, UnloadController)
from rosgraph_msgs.msg import Log
from std_msgs.msg import Float64MultiArray

STRICT = 2
BEST_EFFORT = 1
WAIT = 60.0   # generous bound of every wait [s]


class CM(object):
    """The services of a controller manager in namespace ``ns``."""

    def __init__(self, ns='/'):
        p = ns.rstrip('/') + '/controller_manager/'
        for name in ('list_controllers', 'list_controller_types', 'load_controller', 'unload_controller',
                     'switch_controller', 'reload_controller_libraries'):
            try:
                rospy.wait_for_service(p + name, WAIT)
            except rospy.ROSException:
                raise AssertionError('service %s did not appear within %.0f s' % (p + name, WAIT))
        self.list_srv = rospy.ServiceProxy(p + 'list_controllers', ListControllers)
        self.types_srv = rospy.ServiceProxy(p + 'list_controller_types', ListControllerTypes)
        self.load_srv = rospy.ServiceProxy(p + 'load_controller', LoadController)
        self.unload_srv = rospy.ServiceProxy(p + 'unload_controller', UnloadController)
        self.switch_srv = rospy.ServiceProxy(p + 'switch_controller', SwitchController)
        self.reload_srv = rospy.ServiceProxy(p + 'reload_controller_libraries', ReloadControllerLibraries)

    def load(self, name):
        return self.load_srv(name).ok

    def unload(self, name):
        return self.unload_srv(name).ok

    def switch(self, start=(), stop=(), strictness=STRICT, start_asap=False, timeout=0.0):
        return self.switch_srv(start_controllers=list(start), stop_controllers=list(stop),
                               strictness=strictness, start_asap=start_asap, timeout=timeout).ok

    def states(self):
        return {c.name: c.state for c in self.list_srv().controller}

    def controllers(self):
        return {c.name: c for c in self.list_srv().controller}

    def wait_states(self, expected, timeout=WAIT):
        """Wait until list_controllers reports exactly ``expected`` ({name: state})."""
        deadline = time.monotonic() + timeout
        while True:
            states = self.states()
            if states == expected:
                return states
            if time.monotonic() > deadline:
                raise AssertionError('controllers are %s, expected %s (waited %.0f s)' % (states, expected, timeout))
            time.sleep(0.1)

    def clear(self):
        """Stop and unload every controller."""
        states = self.states()
        running = [n for n, s in states.items() if s == 'running']
        if running:
            assert self.switch(stop=running, strictness=BEST_EFFORT)
        for n in states:
            assert self.unload(n), 'could not unload %s' % n


class RosoutWatcher(object):
    """Collects /rosout messages of ``node`` (a long-running node, e.g. the controller manager's);
    wait_for(text) returns the first one containing ``text``.

    rostest starts no rosout node, so /rosout is subscribed directly, and the constructor waits
    until the connection to ``node``'s publisher is up: nothing it logs afterwards is missed.
    Messages of a node that has just started may be lost that way: check those on the
    process's own output instead."""

    def __init__(self, node='/dummy_robot_hw'):
        self.cond = threading.Condition()
        self.msgs = []
        self.sub = rospy.Subscriber('/rosout', Log, self._cb, queue_size=1000)
        deadline = time.monotonic() + WAIT
        while not any(getattr(c, 'callerid_pub', None) == node for c in list(self.sub.impl.connections or [])):
            if time.monotonic() > deadline:
                raise AssertionError('no /rosout connection to %s within %.0f s' % (node, WAIT))
            time.sleep(0.05)

    def _cb(self, msg):
        with self.cond:
            self.msgs.append(msg)
            self.cond.notify_all()

    def wait_for(self, text, timeout=WAIT):
        deadline = time.monotonic() + timeout
        with self.cond:
            while True:
                for m in self.msgs:
                    if text in m.msg:
                        return m
                left = deadline - time.monotonic()
                if left <= 0:
                    raise AssertionError('no /rosout message containing %r within %.0f s; last ones: %s'
                                         % (text, timeout, [m.msg for m in self.msgs[-5:]]))
                self.cond.wait(left)


class Latest(object):
    """The last Float64MultiArray of a topic and a count, to wait for fresh ones."""

    def __init__(self, topic):
        self.cond = threading.Condition()
        self.msg = None
        self.count = 0
        self.sub = rospy.Subscriber(topic, Float64MultiArray, self._cb, queue_size=10)

    def _cb(self, msg):
        with self.cond:
            self.msg = msg
            self.count += 1
            self.cond.notify_all()

    def wait(self, predicate, timeout=WAIT):
        deadline = time.monotonic() + timeout
        with self.cond:
            while True:
                if self.msg is not None and predicate(list(self.msg.data)):
                    return list(self.msg.data)
                left = deadline - time.monotonic()
                if left <= 0:
                    raise AssertionError('no matching message within %.0f s (last: %s)'
                                         % (timeout, self.msg and list(self.msg.data)))
                self.cond.wait(left)
