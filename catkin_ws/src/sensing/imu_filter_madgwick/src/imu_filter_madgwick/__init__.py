"""Re-implementation of imu_filter_madgwick (Madgwick orientation filter for ROS 1)."""
