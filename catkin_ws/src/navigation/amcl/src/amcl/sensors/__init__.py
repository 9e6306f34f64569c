"""Odometry and laser models (amcl's sensors/)."""
from .odom import OdomModel, ODOM_MODELS, angle_diff, normalize  # noqa: F401
from .laser import LaserModel, LaserData, LASER_MODELS  # noqa: F401
