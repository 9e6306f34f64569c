"""Finding controller managers and querying and filtering their controllers (the Python API of
ros_control's controller_manager_msgs.utils, which rqt_controller_manager and other tools import).

    >>> get_controller_managers()                 # ['/', '/robot/controller_manager', ...]
    >>> controllers = ControllerLister('/robot/controller_manager')()
    >>> filter_by_type(filter_by_state(controllers, 'running'), 'joint_state_controller/JointStateController')
    >>> get_rosparam_controller_names('/robot')   # names N with a parameter /robot/N/type
"""
import rosservice
from rospy import ServiceProxy

from controller_manager_msgs.srv import ListControllers

# The controller manager's services and their types: a namespace offering all of them is one.
_LIST_CONTROLLERS_STR = 'list_controllers'
cm_services = {
    'list_controllers': 'controller_manager_msgs/ListControllers',
    'list_controller_types': 'controller_manager_msgs/ListControllerTypes',
    'load_controller': 'controller_manager_msgs/LoadController',
    'unload_controller': 'controller_manager_msgs/UnloadController',
    'switch_controller': 'controller_manager_msgs/SwitchController',
    'reload_controller_libraries': 'controller_manager_msgs/ReloadControllerLibraries',
}


def get_controller_managers(namespace='/', initial_guess=None):
    """Sorted namespaces of the controller managers under ``namespace``.

    Namespaces in ``initial_guess`` (typically the previous result) that still offer a
    list_controllers service are kept without the full check of every service; new ones are
    checked with is_controller_manager().
    """
    current = _sloppy_get_controller_managers(namespace)
    found = [ns for ns in (initial_guess or []) if ns in current]
    found += [ns for ns in current if ns not in found and is_controller_manager(ns)]
    return sorted(found)


def is_controller_manager(namespace):
    """True if ``namespace`` offers every controller manager service with its type."""
    cm_ns = namespace if namespace.endswith('/') else namespace + '/'
    return all(_srv_exists(cm_ns + name, srv_type) for name, srv_type in cm_services.items())


def _sloppy_get_controller_managers(namespace):
    """Namespaces under ``namespace`` with a list_controllers service (one master query)."""
    try:
        services = rosservice.get_service_list(namespace=namespace)
    except rosservice.ROSServiceIOException:
        return []
    out = []
    suffix = '/' + _LIST_CONTROLLERS_STR
    for name in services:
        if name.endswith(suffix):
            out.append(name[:-len(suffix)] or '/')
    return out


def _srv_exists(srv_name, srv_type):
    """True if the service ``srv_name`` exists with type ``srv_type`` (one master query)."""
    if not srv_name or not srv_type:
        return False
    try:
        return rosservice.get_service_type(srv_name) == srv_type
    except rosservice.ROSServiceIOException:
        return False


class ControllerManagerLister(object):
    """Callable returning the controller managers under ``namespace`` (cheap to call repeatedly)."""

    def __init__(self, namespace='/'):
        self._ns = namespace
        self._cm_list = []

    def __call__(self):
        self._cm_list = get_controller_managers(self._ns, self._cm_list)
        return self._cm_list


class ControllerLister(object):
    """Callable returning the controllers (controller_manager_msgs/ControllerState) of the
    controller manager at ``namespace``; an empty list when it cannot be reached."""

    def __init__(self, namespace='/controller_manager'):
        self._srv_name = namespace.rstrip('/') + '/' + _LIST_CONTROLLERS_STR
        self._srv = self._make_srv()

    def __call__(self):
        try:
            return self._srv.call().controller
        except Exception:
            self._srv = self._make_srv()  # the manager may have restarted: reconnect once
            try:
                return self._srv.call().controller
            except Exception:
                return []

    def _make_srv(self):
        return ServiceProxy(self._srv_name, ListControllers, persistent=True)


def filter_by_name(ctrl_list, ctrl_name, match_substring=False):
    """Controllers whose name is ``ctrl_name`` (or contains it)."""
    return _filter_by_attr(ctrl_list, 'name', ctrl_name, match_substring)


def filter_by_type(ctrl_list, ctrl_type, match_substring=False):
    """Controllers whose type is ``ctrl_type`` (or contains it)."""
    return _filter_by_attr(ctrl_list, 'type', ctrl_type, match_substring)


def filter_by_state(ctrl_list, ctrl_state, match_substring=False):
    """Controllers whose state is ``ctrl_state`` (or contains it)."""
    return _filter_by_attr(ctrl_list, 'state', ctrl_state, match_substring)


def filter_by_hardware_interface(ctrl_list, hardware_interface, match_substring=False):
    """Controllers claiming resources of ``hardware_interface`` (or of an interface containing it)."""
    out = []
    for ctrl in ctrl_list:
        for res in ctrl.claimed_resources:
            if (hardware_interface in res.hardware_interface if match_substring
                    else res.hardware_interface == hardware_interface):
                out.append(ctrl)
                break
    return out


def filter_by_resources(ctrl_list, resources, hardware_interface=None, match_any=False):
    """Controllers claiming all (``match_any`` False) or any of ``resources`` in one of their
    interfaces (only in ``hardware_interface`` if given)."""
    out = []
    for ctrl in ctrl_list:
        for res in ctrl.claimed_resources:
            if hardware_interface is not None and res.hardware_interface != hardware_interface:
                continue
            hits = [r in res.resources for r in resources]
            if (any(hits) if match_any else all(hits)):
                out.append(ctrl)
                break
    return out


def _filter_by_attr(list_in, attr_name, attr_val, match_substring=False):
    if match_substring:
        return [x for x in list_in if attr_val in getattr(x, attr_name)]
    return [x for x in list_in if getattr(x, attr_name) == attr_val]


def get_rosparam_controller_names(namespace='/'):
    """Sorted names N for which the parameter <namespace>/N/type exists: the controller
    configurations that could be loaded there."""
    import rosparam
    ns = namespace if namespace.endswith('/') else namespace + '/'
    names = []
    for param in rosparam.list_params(namespace):
        if not param.startswith(ns):
            continue
        parts = param[len(ns):].split('/')
        if len(parts) == 2 and parts[1] == 'type':
            names.append(parts[0])
    return sorted(names)
