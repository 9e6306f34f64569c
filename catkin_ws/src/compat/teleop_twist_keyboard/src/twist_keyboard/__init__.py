"""Library of the teleop_twist_keyboard re-implementation: key maps, command state, terminal
key reading and the publishing thread. The node script `teleop_twist_keyboard.py` only wires
them together."""
