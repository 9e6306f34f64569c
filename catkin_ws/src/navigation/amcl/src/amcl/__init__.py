"""amcl: adaptive Monte Carlo localization (a re-implementation of ros-planning/navigation's amcl).

Layout as the original: `pf` (particle filter, KLD sampling), `map` (occupancy map and the
likelihood field), `sensors` (odometry and laser models) have no ROS imports; `convert` is the
one module between ROS messages and the core; `node` is the ROS wrapper."""
