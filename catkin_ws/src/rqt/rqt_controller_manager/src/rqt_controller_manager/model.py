"""What the Controller Manager plugin shows and offers, without Qt or ROS: the rows of the
controller table, the actions of a controller's context menu, the claimed-resources tree."""

# Icon of each state (the original's LEDs: running green, stopped/initialized red, not loaded off).
STATE_ICON = {'running': 'green', 'stopped': 'red', 'initialized': 'red', 'uninitialized': 'off'}

# Context-menu entries by controller state: (label, [operations in order]) as the original.
MENU = {
    'running': [('Stop', ['stop']), ('Stop and Unload', ['stop', 'unload'])],
    'stopped': [('Start again', ['start']), ('Unload', ['unload'])],
    'initialized': [('Start', ['start']), ('Unload', ['unload'])],
    'uninitialized': [('Load', ['load']), ('Load and Start', ['load', 'start'])],
}


def resolve_controllers_ns(cm_ns):
    """Namespace of the controllers' configurations: one level above the controller manager
    ('/robot/controller_manager' -> '/robot', '/controller_manager' -> '/'); a manager at '/'
    keeps '/'."""
    ns = cm_ns.rstrip('/')
    if not ns:
        return '/'
    parent = ns.rsplit('/', 1)[0]
    return parent or '/'


def append_ns(ns, name):
    return (ns.rstrip('/') or '') + '/' + name


class Row(object):
    """A controller as the table shows it (loaded ones come from list_controllers)."""

    def __init__(self, name, state, type_='', claimed_resources=()):
        self.name = name
        self.state = state
        self.type = type_
        self.claimed_resources = list(claimed_resources)

    def __eq__(self, other):
        return (self.name, self.state, self.type) == (other.name, other.state, other.type)

    def __repr__(self):
        return 'Row(%r, %r)' % (self.name, self.state)


def table_rows(loaded, configured):
    """Loaded controllers (objects with name/state/type/claimed_resources) first, then the
    configured names (name -> type) not loaded, as 'uninitialized'."""
    rows = [Row(c.name, c.state, c.type, c.claimed_resources) for c in loaded]
    names = set(r.name for r in rows)
    for name in sorted(configured):
        if name not in names:
            rows.append(Row(name, 'uninitialized', configured[name]))
    return rows


def menu_for(state):
    """[(label, operations)] of a controller in ``state`` (empty for unknown states)."""
    return MENU.get(state, [])


def resource_tree(row):
    """('Claimed Resources', [(hardware_interface, [resources])]) of a row."""
    return ('Claimed Resources', [(r.hardware_interface, list(r.resources)) for r in row.claimed_resources])
