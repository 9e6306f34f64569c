"""Lab 3's view of RViz: its config's displays and fixed frame, its command line (no rospy)."""
import os

import yaml

from grading.urdf import ModelError

RVIZ_NEEDED = (('rviz/RobotModel', 'RobotModel'), ('rviz/TF', 'TF'))


def rviz_displays(text):
    """(display classes, fixed frame) of an .rviz YAML config; ModelError if unreadable."""
    try:
        cfg = yaml.safe_load(text)
    except yaml.YAMLError as e:
        raise ModelError('not YAML: %s' % str(e).splitlines()[0])
    vm = (cfg or {}).get('Visualization Manager') if isinstance(cfg, dict) else None
    if not isinstance(vm, dict):
        raise ModelError('no "Visualization Manager" section')
    classes = []

    def walk(displays):
        for d in displays or []:
            if isinstance(d, dict):
                if d.get('Enabled', True) is not False:
                    classes.append(str(d.get('Class', '')))
                walk(d.get('Displays'))
    walk(vm.get('Displays'))
    frame = (vm.get('Global Options') or {}).get('Fixed Frame')
    return classes, frame


def rviz_config_arg(argv):
    """The -d/--display-config file of an rviz command line, or None."""
    for i, a in enumerate(argv):
        if a in ('-d', '--display-config') and i + 1 < len(argv):
            return argv[i + 1]
        if a.startswith('--display-config='):
            return a.split('=', 1)[1]
        if a.startswith('-d') and len(a) > 2:
            return a[2:]
    return None


def node_kind(argv):
    """'robot_state_publisher', 'joint_state_publisher', 'rviz' or None from a command line."""
    names = [os.path.basename(a) for a in argv[:2]]
    for n in names:
        if n in ('robot_state_publisher', 'state_publisher'):
            return 'robot_state_publisher'
        if n in ('joint_state_publisher', 'joint_state_publisher_gui'):
            return 'joint_state_publisher'
        if n == 'rviz':
            return 'rviz'
    return None
