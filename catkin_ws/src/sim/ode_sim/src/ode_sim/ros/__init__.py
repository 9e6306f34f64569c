"""The ROS side: the node (loop, pacing, /clock), the /gazebo/* API, the plugins' ROS wrappers
and the one conversion module between messages and engine types (convert)."""
