"""ROS wiring of the spawner and unspawner scripts (the logic is in spawner.py)."""
import argparse
import signal
import threading
import time

import rospy
from controller_manager_msgs.srv import LoadController, SwitchController, UnloadController
from std_msgs.msg import Bool

from controller_manager import spawner as logic


class RosLog(object):
    info = staticmethod(rospy.loginfo)
    warn = staticmethod(rospy.logwarn)
    error = staticmethod(rospy.logerr)


class RosServices(object):
    """The controller manager's load/switch/unload services under ``prefix``."""

    def __init__(self, prefix):
        self.names = {k: prefix + k for k in ('load_controller', 'switch_controller', 'unload_controller')}
        self.load_srv = rospy.ServiceProxy(self.names['load_controller'], LoadController)
        self.switch_srv = rospy.ServiceProxy(self.names['switch_controller'], SwitchController)
        self.unload_srv = rospy.ServiceProxy(self.names['unload_controller'], UnloadController)

    def wait(self, timeout, stop_event):
        """Wait for the three services; ``timeout`` [s wall] 0 = forever. While /use_sim_time is
        set and no /clock has arrived yet, keep waiting (the simulator is still starting); the
        timeout then counts from the clock's start. False if they did not appear."""
        start = time.monotonic()
        for name in self.names.values():
            rospy.loginfo("Controller Spawner: Waiting for service " + name)
            while not stop_event.is_set() and not rospy.is_shutdown():
                try:
                    rospy.wait_for_service(name, 1.0)
                    break
                except rospy.ROSException:
                    pass
                if timeout > 0 and time.monotonic() - start > timeout:
                    if rospy.get_param('/use_sim_time', False) and rospy.get_rostime().is_zero():
                        rospy.loginfo_throttle(10, "Controller Spawner: waiting for the simulator: "
                                               "/use_sim_time is set and no /clock has been received yet")
                        start = time.monotonic()   # the timeout counts from the clock's start
                        continue
                    return False
            else:
                return False
        return True

    def load(self, name):
        return self.load_srv(name).ok

    def switch(self, start, stop, strictness):
        return self.switch_srv(start_controllers=start, stop_controllers=stop, strictness=strictness,
                               start_asap=False, timeout=0.0).ok

    def unload(self, name):
        return self.unload_srv(name).ok


def _wait_for_true(topic, stop_event):
    got = threading.Event()

    def callback(msg):
        if msg.data:
            got.set()

    sub = rospy.Subscriber(topic, Bool, callback)
    rospy.loginfo("Controller Spawner: Waiting for %s to be True" % topic)
    while not got.wait(0.1):
        if stop_event.is_set() or rospy.is_shutdown():
            sub.unregister()
            return False
    sub.unregister()
    return True


def _install_stop_signals(stop_event):
    """SIGINT/SIGTERM only set ``stop_event``: the main thread then finishes the service call it
    is in, tears down, and shuts rospy down itself (rospy's own handlers are disabled)."""
    def handler(signum, frame):
        stop_event.set()
    signal.signal(signal.SIGINT, handler)
    signal.signal(signal.SIGTERM, handler)


def spawner_main(argv):
    rospy.init_node('spawner', anonymous=True, disable_signals=True)
    stop_event = threading.Event()
    _install_stop_signals(stop_event)
    rospy.on_shutdown(stop_event.set)
    args = logic.parse_args(rospy.myargv(argv)[1:])
    if args.shutdown_timeout is not None:
        rospy.logwarn("Controller Spawner: --shutdown-timeout is deprecated and ignored")

    prefix = logic.service_prefix(args.namespace)
    services = RosServices(prefix)
    try:
        if not services.wait(args.timeout, stop_event):
            if not stop_event.is_set() and not rospy.is_shutdown():
                rospy.logwarn("Controller Spawner couldn't find the expected controller_manager ROS interface.")
            return 0
        if args.wait_for and not _wait_for_true(args.wait_for, stop_event):
            return 0

        param_ns = args.namespace or rospy.get_namespace()
        try:
            names = logic.expand_controllers(
                args.controllers, lambda key, value: rospy.set_param(param_ns.rstrip('/') + '/' + key, value))
        except logic.SpawnerError as exc:
            rospy.logerr("Controller Spawner: %s" % exc)
            return 1

        spawner = logic.Spawner(services, RosLog, autostart=not args.stopped)
        # rosnode kill / master shutdown: tear down from rospy's pre-shutdown hook (services still work)
        rospy.on_shutdown(spawner.teardown)
        spawner.load_all(names, stop_event.is_set)
        if not stop_event.is_set():
            spawner.start_all()
        while not stop_event.wait(0.2):
            pass
        spawner.teardown()
        return 0
    finally:
        rospy.signal_shutdown('spawner done')


def unspawner_main(argv):
    """Stop the given controllers now, start them again when this node shuts down."""
    rospy.init_node('unspawner', anonymous=True, disable_signals=True)
    stop_event = threading.Event()
    _install_stop_signals(stop_event)
    rospy.on_shutdown(stop_event.set)
    p = argparse.ArgumentParser(prog='unspawner', description='stops controllers while it runs')
    p.add_argument('controllers', metavar='controller', nargs='+', help='controllers to stop')
    p.add_argument('--namespace', metavar='ns', help='namespace of the controller_manager services')
    args = p.parse_args(rospy.myargv(argv)[1:])
    services = RosServices(logic.service_prefix(args.namespace))
    if not services.wait(0.0, stop_event):
        rospy.signal_shutdown('unspawner done')
        return 0
    stopped = []

    def restart():
        if stopped:
            names = list(stopped)
            del stopped[:]
            try:
                if services.switch(names, [], logic.STRICT):
                    rospy.loginfo("Restarted controllers: %s" % ', '.join(names))
                else:
                    rospy.logerr("Failed to restart controllers: %s" % ', '.join(names))
            except Exception as exc:
                rospy.logwarn("Unspawner error while restarting controllers: %s" % exc)

    rospy.on_shutdown(restart)
    if services.switch([], args.controllers, logic.STRICT):
        stopped.extend(args.controllers)
        rospy.loginfo("Stopped controllers: %s" % ', '.join(args.controllers))
    else:
        rospy.logerr("Failed to stop controllers: %s" % ', '.join(args.controllers))
    while not stop_event.wait(0.2):
        pass
    restart()
    rospy.signal_shutdown('unspawner done')
    return 0
