"""explore_lite re-implemented: greedy frontier exploration on a costmap, goals through move_base."""
