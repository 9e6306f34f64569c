"""my_robot_model: the course's first robot model (practical work 3) and model-checking helpers."""
