"""Built-in plugins, selected by the `filename` of a URDF/SDF <plugin> tag.

REGISTRY maps file names to classes; modules register themselves on import (see _load()).
"""
import importlib

REGISTRY = {}

# module -> file names it provides (imported lazily: sensors pull in OpenGL only when used)
MODULES = {
    'drive': ['libgazebo_ros_diff_drive.so', 'libgazebo_ros_skid_steer_drive.so'],
    'state': ['libgazebo_ros_p3d.so', 'libgazebo_ros_joint_state_publisher.so'],
    'imu': ['libgazebo_ros_imu.so', 'libgazebo_ros_imu_sensor.so'],
    'laser': ['libgazebo_ros_laser.so', 'libgazebo_ros_gpu_laser.so'],
    'camera': ['libgazebo_ros_camera.so', 'libgazebo_ros_openni_kinect.so',
               'libgazebo_ros_depth_camera.so'],
    'control': ['libgazebo_ros_control.so'],
    'contact': ['libgazebo_ros_bumper.so'],
    'range': ['libgazebo_ros_range.so'],
    'block_laser': ['libgazebo_ros_block_laser.so'],
    'triggered_camera': ['libgazebo_ros_triggered_camera.so'],
    'multicamera': ['libgazebo_ros_multicamera.so'],
    'gps': ['libhector_gazebo_ros_gps.so', 'libgazebo_ros_gps.so'],
    'motion': ['libgazebo_ros_planar_move.so', 'libgazebo_ros_force.so',
               'libgazebo_ros_vacuum_gripper.so', 'libgazebo_ros_joint_pose_trajectory.so'],
}


def known():
    return sorted(f for files in MODULES.values() for f in files)


def lookup(filename):
    """The plugin class for a file name, or None if ode_sim has no such plugin."""
    base = filename.rsplit('/', 1)[-1]
    if base in REGISTRY:
        return REGISTRY[base]
    for mod, files in MODULES.items():
        if base in files:
            m = importlib.import_module('%s.%s' % (__name__, mod))
            REGISTRY.update(getattr(m, 'PLUGINS'))
            return REGISTRY.get(base)
    return None
