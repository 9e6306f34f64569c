"""Practical work 6 (my_robot_simulation_sensors): camera and lidar data processing."""
