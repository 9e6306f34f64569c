"""Practical work 4 (my_robot_simulation): helpers behind scripts/drive.py."""
