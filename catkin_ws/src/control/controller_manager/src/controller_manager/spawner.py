"""Logic of the ``spawner`` script: load (and start) controllers, stop and unload them on exit.

``Spawner`` talks to the controller manager through a ``services`` object (load, switch,
unload: each returns the service's ``ok``), so its behaviour is testable without a ROS master;
``RosServices`` is the real one.
"""
import argparse
import os
import threading

import yaml

STRICT = 2
BEST_EFFORT = 1


def build_parser():
    p = argparse.ArgumentParser(prog='spawner', description='Controller spawner: loads and starts the '
                                'given controllers; stops and unloads them when it is shut down')
    p.add_argument('controllers', metavar='controller', nargs='+',
                   help='controllers to load (names, or paths of YAML files whose top-level keys are controllers)')
    p.add_argument('--stopped', action='store_true', help='loads controllers, but does not start them')
    p.add_argument('--wait-for', metavar='topic',
                   help='does not load or start controllers until it hears "True" on a topic (Bool)')
    p.add_argument('--namespace', metavar='ns', help='namespace of the controller_manager services')
    p.add_argument('--no-timeout', action='store_true', help='wait for the controller_manager services forever')
    p.add_argument('--timeout', metavar='T', type=float, default=30,
                   help='how long to wait for controller_manager services when starting up [s] '
                        '(default: 30). <= 0 waits forever')
    p.add_argument('--shutdown-timeout', metavar='SHUTDOWN_TIMEOUT', type=float, default=None,
                   help='DEPRECATED, ignored')
    return p


def parse_args(argv):
    """Arguments (remappings already stripped) → argparse namespace; ``timeout`` 0 = forever."""
    args = build_parser().parse_args(argv)
    if args.no_timeout or args.timeout <= 0:
        args.timeout = 0.0
    return args


def service_prefix(namespace):
    """'NS/controller_manager/' or 'controller_manager/' (resolved in the node's namespace)."""
    if namespace:
        return namespace.rstrip('/') + '/controller_manager/'
    return 'controller_manager/'


class SpawnerError(Exception):
    """A spawner argument that cannot be used (e.g. an unreadable YAML file)."""


def expand_controllers(names, set_param, exists=os.path.exists, read=None):
    """Controller names from the arguments: a path of an existing file is read as YAML, its
    top-level keys are set as parameters (``set_param(key, value)``) and become the names."""
    read = read or (lambda path: open(path).read())
    out = []
    for name in names:
        if exists(name):
            try:
                content = yaml.safe_load(read(name))
            except (OSError, yaml.YAMLError) as exc:
                raise SpawnerError('cannot read controller configuration %s: %s' % (name, exc))
            if not isinstance(content, dict):
                raise SpawnerError('controller configuration %s: expected a mapping of controller names '
                                   'at the top level, got %s' % (name, type(content).__name__))
            for key, value in content.items():
                set_param(str(key), value)
                out.append(str(key))
        else:
            out.append(name)
    return out


class Spawner(object):
    """Load, start, and on shutdown stop and unload controllers through ``services``."""

    def __init__(self, services, log, autostart=True):
        self.services = services
        self.log = log          # object with info/warn/error(str)
        self.autostart = autostart
        self.loaded = []
        self.started = False
        self._torn_down = False
        self._lock = threading.Lock()

    def load_all(self, names, stop_requested=lambda: False):
        for name in names:
            if stop_requested():
                break
            self.log.info("Loading controller: " + name)
            if self.services.load(name):
                self.loaded.append(name)
            else:
                self.log.error("Failed to load %s" % name)
        self.log.info("Controller Spawner: Loaded controllers: %s" % ', '.join(self.loaded))
        return self.loaded

    def start_all(self):
        if not self.autostart or not self.loaded:
            return True
        if self.services.switch(list(self.loaded), [], STRICT):
            self.started = True
            self.log.info("Started controllers: %s" % ', '.join(self.loaded))
            return True
        self.log.error("Failed to start controllers: %s" % ', '.join(self.loaded))
        return False

    def teardown(self):
        """Stop the loaded controllers and unload them in reverse order (once)."""
        with self._lock:
            if self._torn_down:
                return
            self._torn_down = True
            if self.loaded:
                self._teardown()

    def _teardown(self):
        self.log.info("Shutting down spawner. Stopping and unloading controllers...")
        try:
            self.log.info("Stopping all controllers...")
            strictness = STRICT if self.started else BEST_EFFORT
            if not self.services.switch([], list(self.loaded), strictness):
                self.log.warn("Controller Spawner: could not stop controllers: %s" % ', '.join(self.loaded))
            for name in reversed(self.loaded):
                self.log.info("Trying to unload %s" % name)
                if self.services.unload(name):
                    self.log.info("Succeeded in unloading %s" % name)
                else:
                    self.log.warn("Controller Spawner: failed to unload %s" % name)
        except Exception as exc:  # service or ROS errors while the system goes down
            self.log.warn("Controller Spawner error while taking down controllers: %s" % exc)
