"""slam_gmapping's ROS-free core: an RBPF grid SLAM (GridSlam) after openslam gmapping."""
