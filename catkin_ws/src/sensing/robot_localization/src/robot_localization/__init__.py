"""Re-implementation of robot_localization's ekf_localization_node (Python node, C++ EKF core)."""
