"""ode_sim_gui: the simulator's window (gzclient), a client of ode_sim's /gazebo API."""
