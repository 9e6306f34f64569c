"""tf_compat: the textbook's `rosrun tf view_frames` on Debian's ROS (Python 3)."""
