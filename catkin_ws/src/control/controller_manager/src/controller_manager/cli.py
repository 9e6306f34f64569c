"""Logic of the ``controller_manager`` command-line tool.

    controller_manager <command> [args]
      lt, list-types              list the controller types that can be loaded
      lc, list                    list the loaded controllers with their state
      reload-libraries [--restore]
      load NAME...                load controllers
      unload NAME...              unload controllers
      start NAME...               start controllers
      stop NAME...                stop controllers
      sp, spawn NAME...           load and start controllers
      kl, kill NAME...            stop and unload controllers
"""
from __future__ import print_function

import sys

USAGE = __doc__.split('\n\n', 1)[1].rstrip()

COMMANDS = {
    'lt': 'list-types', 'list-types': 'list-types',
    'lc': 'list', 'list': 'list',
    'reload-libraries': 'reload-libraries',
    'load': 'load', 'unload': 'unload', 'start': 'start', 'stop': 'stop',
    'sp': 'spawn', 'spawn': 'spawn',
    'kl': 'kill', 'kill': 'kill',
}
NEEDS_NAMES = {'load', 'unload', 'start', 'stop', 'spawn', 'kill'}


class UsageError(Exception):
    pass


def parse(argv):
    """argv (without the program name) → (command, names, options)."""
    if not argv:
        raise UsageError('no command given')
    cmd = COMMANDS.get(argv[0])
    if cmd is None:
        raise UsageError("unknown command '%s'" % argv[0])
    rest = argv[1:]
    options = {'restore': False}
    if cmd == 'reload-libraries':
        for a in rest:
            if a == '--restore':
                options['restore'] = True
            else:
                raise UsageError("reload-libraries: unknown argument '%s'" % a)
        rest = []
    elif cmd in NEEDS_NAMES and not rest:
        raise UsageError('%s: give at least one controller name' % cmd)
    elif cmd not in NEEDS_NAMES and rest:
        raise UsageError("%s takes no arguments" % cmd)
    return cmd, rest, options


def run(cmd, names, options, api):
    """Run a parsed command with ``api`` (controller_manager_interface or a fake); True = success."""
    if cmd == 'list-types':
        api.list_controller_types()
        return True
    if cmd == 'list':
        api.list_controllers()
        return True
    if cmd == 'reload-libraries':
        return bool(api.reload_libraries(force_kill=options['restore'], restore=options['restore']))
    ok = True
    for name in names:
        if cmd == 'load':
            ok = api.load_controller(name) and ok
        elif cmd == 'unload':
            ok = api.unload_controller(name) and ok
        elif cmd == 'start':
            ok = api.start_controller(name) and ok
        elif cmd == 'stop':
            ok = api.stop_controller(name) and ok
        elif cmd == 'spawn':
            ok = api.load_controller(name) and api.start_controller(name) and ok
        elif cmd == 'kill':
            ok = api.stop_controller(name) and api.unload_controller(name) and ok
    return bool(ok)


def main(argv, api=None):
    try:
        cmd, names, options = parse(argv)
    except UsageError as exc:
        print('controller_manager: %s' % exc, file=sys.stderr)
        print(USAGE, file=sys.stderr)
        return 2
    if api is None:  # service proxies need no node: nothing is registered with the master
        from controller_manager import controller_manager_interface as api
    return 0 if run(cmd, names, options, api) else 1
