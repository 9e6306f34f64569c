"""gazebo_ros (re-implementation for ode_sim): spawn_model, gzclient, and the client helpers of
the original's gazebo_interface module."""
