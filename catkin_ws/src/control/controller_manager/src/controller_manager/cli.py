"""Logic of the ``controller_manager`` command-line tool (as ros_control's script).

    controller_manager <command> [names]
"""
from __future__ import print_function

import sys

USAGE = '''Commands:
    load <name>          - Load the controller named <name>
    unload <name>        - Unload the controller named <name>
    start <name>         - Start the controller named <name>
    stop <name>          - Stop the controller named <name>
    spawn <name>         - Load and start the controller named <name>
    kill <name>          - Stop and unload the controller named <name>
    list                 - List active controllers
    list-types           - List controller Types
    reload-libraries     - Reloads all plugin controller libraries'''

COMMANDS = {
    'lt': 'list-types', 'list-types': 'list-types',
    'lc': 'list', 'list': 'list',
    'reload-libraries': 'reload-libraries',
    'load': 'load', 'unload': 'unload', 'start': 'start', 'stop': 'stop',
    'sp': 'spawn', 'spawn': 'spawn',
    'kl': 'kill', 'kill': 'kill',
}


class UsageError(Exception):
    pass


def parse(argv):
    """argv (without the program name) → (command, names, options). No command → (None, [], {})."""
    if not argv:
        return None, [], {}
    cmd = COMMANDS.get(argv[0])
    if cmd is None:
        raise UsageError("unknown command '%s'" % argv[0])
    rest = argv[1:]
    options = {'restore': False}
    if cmd == 'reload-libraries':
        options['restore'] = '--restore' in rest
        rest = []
    return cmd, rest, options


def run(cmd, names, options, api):
    """Run a parsed command with ``api`` (controller_manager_interface or a fake); True = success.
    As the original: ``spawn`` loads every name then starts each, ``kill`` stops every name then
    unloads each, ``reload-libraries`` always force-kills the loaded controllers."""
    if cmd == 'list-types':
        api.list_controller_types()
        return True
    if cmd == 'list':
        api.list_controllers()
        return True
    if cmd == 'reload-libraries':
        return bool(api.reload_libraries(True, restore=options['restore']))
    ok = True
    steps = {'load': ['load_controller'], 'unload': ['unload_controller'], 'start': ['start_controller'],
             'stop': ['stop_controller'], 'spawn': ['load_controller', 'start_controller'],
             'kill': ['stop_controller', 'unload_controller']}[cmd]
    for step in steps:
        for name in names:
            ok = bool(getattr(api, step)(name)) and ok
    return ok


def main(argv, api=None):
    """Exit status: 0 done, 1 a service refused or an unknown command (after the usage text)."""
    try:
        cmd, names, options = parse(argv)
    except UsageError as exc:
        print('controller_manager: %s' % exc, file=sys.stderr)
        print(USAGE)
        return 1
    if cmd is None:
        print(USAGE)
        return 0
    if api is None:  # service proxies need no node: nothing is registered with the master
        from controller_manager import controller_manager_interface as api
    return 0 if run(cmd, names, options, api) else 1
