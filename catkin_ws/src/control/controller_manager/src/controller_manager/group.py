"""controller_group's logic (ros_control's `controller_group list|spawn|switch GROUP`): groups of
controllers from the `controller_groups` parameter (group name -> list of controller names),
spawning one group and switching between groups in one STRICT switch.

The functions take the parameter's value and a controller manager interface (load, list,
start, start_stop: controller_manager_interface's functions, or fakes in tests), so they run
without a master. Output is the original's: `Number of groups: N`, the group names and their
controllers indented, `There is no controller defined in group G` (an error) and `Cancel group
switching` when a controller of the group cannot be loaded."""
from __future__ import print_function

import argparse


def read_group(groups, group, logerr):
    """(controllers of `group`, controllers of the other groups not in it), or (None, None)
    with an error line when the group is empty or missing."""
    groups = groups if isinstance(groups, dict) else {}
    desired = set(groups.get(group) or ())
    if not desired:
        logerr('There is no controller defined in group {}'.format(group))
        return None, None
    everything = set()
    for controllers in groups.values():
        everything.update(controllers or ())
    return desired, everything - desired


def list_groups(groups, out=print):
    groups = groups if isinstance(groups, dict) else {}
    out('Number of groups: {}'.format(len(groups)))
    for group, controllers in sorted(groups.items()):
        out('  {}'.format(group))
        for controller in controllers or ():
            out('      {}'.format(controller))


def loaded_controllers(cm, logerr):
    """{name: running} of the controllers the manager has loaded."""
    states = {}
    for c in cm.list():
        states[c.name] = c.state == 'running'
        if c.state not in ('running', 'stopped'):
            logerr('Unknown controller state {}'.format(c.state))
    return states


def spawn_group(groups, group, cm, logerr):
    """Load every controller of the group, then start each. False when the group is empty."""
    desired, _ = read_group(groups, group, logerr)
    if not desired:
        return False
    for name in sorted(desired):
        cm.load(name)
    for name in sorted(desired):
        cm.start(name)
    return True


def switch_group(groups, group, cm, logerr, out=print):
    """Stop the running controllers of the other groups and start (loading if needed) the
    group's own, in one switch. False when the group is empty or a load fails."""
    desired, others = read_group(groups, group, logerr)
    if not desired:
        return False
    loaded = loaded_controllers(cm, logerr)
    to_stop = sorted(c for c in others if loaded.get(c, False))
    to_start = []
    for name in sorted(desired):
        if name not in loaded and not cm.load(name):
            out('Cancel group switching')
            return False
        if not loaded.get(name, False):
            to_start.append(name)
    return cm.start_stop(to_start, to_stop)


def parser():
    p = argparse.ArgumentParser(prog='controller_group', description='Controller Group Utility')
    sub = p.add_subparsers(title='Commands', metavar='', dest='command')
    sub.required = True
    sub.add_parser('list', help='list available groups')
    s = sub.add_parser('spawn', help='load all controllers in all groups and start controllers '
                                     'in the specified group')
    s.add_argument('group', help='name of the group to start')
    s = sub.add_parser('switch', help='switch to the specified group')
    s.add_argument('group', help='name of the group to switch to')
    return p


class RosControllerManager(object):
    """The controller manager of this node's namespace through controller_manager_interface."""

    def __init__(self):
        from controller_manager import controller_manager_interface as cmi
        import rospy
        from controller_manager_msgs.srv import ListControllers, ListControllersRequest
        self._cmi = cmi
        self._rospy = rospy
        self._list = (ListControllers, ListControllersRequest)

    def list(self):
        srv, req = self._list
        name = self._cmi.service_name('list_controllers')
        self._rospy.wait_for_service(name, timeout=5)
        return self._rospy.ServiceProxy(name, srv)(req()).controller

    def load(self, name):
        return self._cmi.load_controller(name)

    def start(self, name):
        return self._cmi.start_controller(name)

    def start_stop(self, start, stop):
        return self._cmi.start_stop_controllers(start_controllers=start, stop_controllers=stop)


def main(argv):
    import rospy
    args = parser().parse_args(rospy.myargv(argv)[1:])
    groups = rospy.get_param('controller_groups', {})
    if args.command == 'list':
        list_groups(groups)
        return 0
    cm = RosControllerManager()
    run = spawn_group if args.command == 'spawn' else switch_group
    return 0 if run(groups, args.group, cm, rospy.logerr) else 1
