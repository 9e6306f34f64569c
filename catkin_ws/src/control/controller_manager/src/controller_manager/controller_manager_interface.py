"""Helpers that call a controller manager's services (as ros_control's controller_manager_interface).

Service names are relative ('controller_manager/load_controller'), so they resolve in the
caller's namespace (ROS_NAMESPACE or __ns:=); every function also takes an optional
``namespace``. They print what happened in the original's words and return the service's result:

    'name' - 'hardware_interface::EffortJointInterface' ( running )     (list_controllers)
    Loaded 'name' / Error when loading 'name'
    Unloaded 'name' successfully / Error when unloading 'name'
    Started ['name'] successfully / Stopped ['name'] successfully
    Error when starting ['a'] and stopping []
    Restore: False / Successfully reloaded libraries
"""
from __future__ import print_function

import rospy
from controller_manager_msgs.srv import (ListControllers, ListControllersRequest, ListControllerTypes,
                                         ListControllerTypesRequest, LoadController, LoadControllerRequest,
                                         ReloadControllerLibraries, ReloadControllerLibrariesRequest,
                                         SwitchController, SwitchControllerRequest, UnloadController,
                                         UnloadControllerRequest)

STRICT = SwitchControllerRequest.STRICT
BEST_EFFORT = SwitchControllerRequest.BEST_EFFORT


def service_name(service, namespace=None):
    """'controller_manager/<service>' under ``namespace`` (relative name when it is empty)."""
    if namespace:
        return namespace.rstrip('/') + '/controller_manager/' + service
    return 'controller_manager/' + service


def _proxy(service, srv_type, namespace=None, wait=True):
    name = service_name(service, namespace)
    if wait:
        rospy.wait_for_service(name)
    return rospy.ServiceProxy(name, srv_type)


def format_controller(c):
    """One line of ``list``: 'name' - 'iface[+iface…]' ( state )."""
    hwi = sorted(set(r.hardware_interface for r in c.claimed_resources))
    return "'%s' - '%s' ( %s )" % (c.name, '+'.join(hwi), c.state)


def list_controller_types(namespace=None):
    resp = _proxy('list_controller_types', ListControllerTypes, namespace).call(ListControllerTypesRequest())
    for t in resp.types:
        print(t)
    return resp.types


def list_controllers(namespace=None):
    resp = _proxy('list_controllers', ListControllers, namespace).call(ListControllersRequest())
    if not resp.controller:
        print("No controllers are loaded in mechanism control")
    for c in resp.controller:
        print(format_controller(c))
    return resp.controller


def load_controller(name, namespace=None):
    resp = _proxy('load_controller', LoadController, namespace).call(LoadControllerRequest(name))
    if resp.ok:
        print("Loaded '%s'" % name)
        return True
    print("Error when loading '%s'" % name)
    return False


def unload_controller(name, namespace=None):
    resp = _proxy('unload_controller', UnloadController, namespace).call(UnloadControllerRequest(name))
    if resp.ok:
        print("Unloaded '%s' successfully" % name)
        return True
    print("Error when unloading '%s'" % name)
    return False


def start_stop_controllers(start_controllers=[], stop_controllers=[], namespace=None):  # noqa: B006 (as the original)
    """One STRICT switch that starts ``start_controllers`` and stops ``stop_controllers``.

    The pre-Noetic form ``start_stop_controllers(names, st)`` (``st`` True = start) is accepted too.
    """
    if isinstance(stop_controllers, bool):
        names, st = start_controllers, stop_controllers
        start_controllers, stop_controllers = (names, []) if st else ([], names)
    resp = _proxy('switch_controller', SwitchController, namespace).call(
        SwitchControllerRequest(start_controllers=start_controllers, stop_controllers=stop_controllers,
                                strictness=STRICT, start_asap=False, timeout=0.0))
    if resp.ok:
        if start_controllers:
            print("Started {} successfully".format(start_controllers))
        if stop_controllers:
            print("Stopped {} successfully".format(stop_controllers))
        return True
    print("Error when starting {} and stopping {}".format(start_controllers, stop_controllers))
    return False


def start_controller(name, namespace=None):
    return start_stop_controllers(start_controllers=[name], namespace=namespace)


def start_controllers(names, namespace=None):
    return start_stop_controllers(start_controllers=names, namespace=namespace)


def stop_controller(name, namespace=None):
    return start_stop_controllers(stop_controllers=[name], namespace=namespace)


def stop_controllers(names, namespace=None):
    return start_stop_controllers(stop_controllers=names, namespace=namespace)


def reload_libraries(force_kill, restore=False, namespace=None):
    """Reload the controller plugin libraries (``force_kill``: stop and unload every controller
    first). With ``restore`` the controllers loaded before are loaded again and the running ones
    restarted (BEST_EFFORT). Returns whether the reload itself succeeded."""
    srv = _proxy('reload_controller_libraries', ReloadControllerLibraries, namespace)
    list_srv = _proxy('list_controllers', ListControllers, namespace, wait=False)
    load_srv = _proxy('load_controller', LoadController, namespace, wait=False)
    switch_srv = _proxy('switch_controller', SwitchController, namespace, wait=False)

    print("Restore: " + str(restore))
    if restore:
        originally = list_srv.call(ListControllersRequest())

    resp = srv.call(ReloadControllerLibrariesRequest(force_kill))
    if resp.ok:
        print("Successfully reloaded libraries")
        result = True
    else:
        print("Failed to reload libraries. Do you still have controllers loaded?")
        result = False

    if restore:
        for c in originally.controller:
            load_srv(c.name)
        to_start = [c.name for c in originally.controller if c.state == 'running']
        switch_srv(start_controllers=to_start, stop_controllers=[], strictness=BEST_EFFORT,
                   start_asap=False, timeout=0.0)
        print("Controllers restored to original state")
    return result
