"""ode_sim: an ODE-based simulator with Gazebo classic's ROS surface (see the package README)."""
