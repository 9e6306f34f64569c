"""Occupancy map with the likelihood-field distance map (amcl's map/)."""
from .map import Map, OCC_FREE, OCC_UNKNOWN, OCC_OCCUPIED  # noqa: F401
