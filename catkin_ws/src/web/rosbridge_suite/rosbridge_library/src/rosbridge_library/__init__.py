"""rosbridge_library: the rosbridge v2 protocol (re-implementation), ROS-free except for
internal/ros_backend.py."""
