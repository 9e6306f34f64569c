"""Helpers that call a controller manager's services (as ros_control's controller_manager_interface).

Service names are relative ('controller_manager/load_controller'), so they resolve in the
caller's namespace; every function takes an optional ``namespace`` too. They print what
happened, as the upstream helpers do, and return the service's result.
"""
from __future__ import print_function

import rospy
from controller_manager_msgs.srv import (ListControllers, ListControllerTypes, LoadController,
                                         ReloadControllerLibraries, SwitchController,
                                         SwitchControllerRequest, UnloadController)

STRICT = SwitchControllerRequest.STRICT
BEST_EFFORT = SwitchControllerRequest.BEST_EFFORT


def service_name(service, namespace=None):
    """'controller_manager/<service>' under ``namespace`` (relative name when it is empty)."""
    if namespace:
        return namespace.rstrip('/') + '/controller_manager/' + service
    return 'controller_manager/' + service


def _proxy(service, srv_type, namespace=None):
    name = service_name(service, namespace)
    rospy.wait_for_service(name)
    return rospy.ServiceProxy(name, srv_type)


def list_controller_types(namespace=None):
    resp = _proxy('list_controller_types', ListControllerTypes, namespace).call()
    for t in resp.types:
        print(t)
    return resp.types


def list_controllers(namespace=None):
    resp = _proxy('list_controllers', ListControllers, namespace).call()
    if not resp.controller:
        print("No controllers are loaded in mechanism control")
    for c in resp.controller:
        hwi = sorted(set(r.hardware_interface for r in c.claimed_resources))
        print('%s - %s ( %s )' % (c.name, '+'.join(hwi), c.state))
    return resp.controller


def load_controller(name, namespace=None):
    resp = _proxy('load_controller', LoadController, namespace).call(name)
    if resp.ok:
        print("Loaded", name)
    else:
        print("Error when loading", name)
    return resp.ok


def unload_controller(name, namespace=None):
    resp = _proxy('unload_controller', UnloadController, namespace).call(name)
    if resp.ok:
        print("Unloaded %s successfully" % name)
    else:
        print("Error when unloading", name)
    return resp.ok


def start_stop_controllers(names, st, namespace=None):
    """Start (``st`` True) or stop the controllers ``names`` in one STRICT switch."""
    start = list(names) if st else []
    stop = [] if st else list(names)
    resp = _proxy('switch_controller', SwitchController, namespace).call(
        SwitchControllerRequest(start_controllers=start, stop_controllers=stop, strictness=STRICT,
                                start_asap=False, timeout=0.0))
    verb = 'start' if st else 'stopp'
    if resp.ok:
        for n in names:
            print("%sed %s successfully" % (verb.capitalize(), n))
    else:
        print("Error when %sing" % verb, ', '.join(names))
    return resp.ok


def start_controller(name, namespace=None):
    return start_stop_controllers([name], True, namespace)


def stop_controller(name, namespace=None):
    return start_stop_controllers([name], False, namespace)


def reload_libraries(force_kill=False, restore=False, namespace=None):
    """Reload the controller plugin libraries. With ``restore`` the loaded controllers are
    loaded again afterwards and the running ones restarted (implies killing them first)."""
    if restore:
        force_kill = True
        controllers = _proxy('list_controllers', ListControllers, namespace).call().controller
    resp = _proxy('reload_controller_libraries', ReloadControllerLibraries, namespace).call(force_kill)
    if resp.ok:
        print("Successfully reloaded libraries")
    else:
        print("Failed to reload libraries. Do you still have controllers loaded?")
        return False
    if restore:
        ok = True
        for c in controllers:
            ok = load_controller(c.name, namespace) and ok
        running = [c.name for c in controllers if c.state == 'running']
        if running:
            ok = start_stop_controllers(running, True, namespace) and ok
        if ok:
            print("Restored controllers")
        return ok
    return True
