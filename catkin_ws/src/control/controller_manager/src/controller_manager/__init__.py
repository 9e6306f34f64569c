"""Python side of the controller_manager re-implementation (ros_control Noetic 0.20 surface).

controller_manager_interface: the upstream module-level helpers (load/unload/start/stop/list...).
spawner, unspawner, cli: the logic of the scripts of the same names.
"""
