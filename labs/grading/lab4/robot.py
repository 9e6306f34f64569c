"""Lab 4's robot: drive plugins in its description, its wheels, what its controllers command (no rospy)."""
import xml.etree.ElementTree as ET

DRIVE_PLUGINS = ('diff_drive', 'skid_steer', 'planar_move', 'tricycle')


# controllers of ros_controllers whose command to a wheel is a velocity (drive controllers
# turn a twist into wheel velocities)
DRIVE_CONTROLLERS = ('diff_drive_controller/DiffDriveController',
                     'four_wheel_steering_controller/FourWheelSteeringController',
                     'ackermann_steering_controller/AckermannSteeringController')
NOT_VELOCITY = ('Position', 'Trajectory', 'Gripper')   # what these controllers command


def commands_velocity(ctype, iface):
    """(True/False, what the controller commands) for a controller of type `ctype` that claims
    a joint under hardware interface `iface`."""
    cls = (ctype or '').split('/')[-1]
    if ctype in DRIVE_CONTROLLERS:
        return True, 'velocity'
    for word in NOT_VELOCITY:
        if word in cls:
            return False, word.lower()
    if 'Velocity' in cls:
        return True, 'velocity'
    if 'Effort' in cls:
        return False, 'effort'
    if (iface or '').endswith('VelocityJointInterface'):
        return True, 'velocity'
    return False, 'a type the grader does not know, under %s' % (iface or 'no interface').split('::')[-1]


def drive_plugins(urdf_text):
    """Filenames of drive plugins in a robot description."""
    try:
        root = ET.fromstring(urdf_text)
    except ET.ParseError:
        return []
    return [p.get('filename', '') for p in root.iter('plugin')
            if any(k in (p.get('filename', '') + p.get('name', '')).lower() for k in DRIVE_PLUGINS)]


def wheel_joints(model):
    return sorted(n for n, j in model['joints'].items()
                  if j['type'] == 'continuous'
                  and 'cylinder' in [c[0] for c in model['links'][j['child']]['collisions']])
