"""The world and model description: SDF / URDF / mesh parsers producing plain data
(ode_sim.description.model), one model lookup (resolve), one error type (ModelError).
No ODE, no ROS."""
