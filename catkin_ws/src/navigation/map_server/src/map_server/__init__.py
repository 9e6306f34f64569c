"""map_server's ROS-free core: map YAML parsing, image <-> occupancy grid conversion, and the
map_saver file writer. Other packages (amcl, costmap helpers) import it:

    from map_server.map_io import load_map, MapError
    grid = load_map('map.yaml')      # Grid: width, height, resolution, origin, data (int8, row 0 = bottom)
"""
from map_server.grid import Grid  # noqa: F401
from map_server.map_io import MapError, load_map, load_image_grid, parse_map_yaml, MapConfig  # noqa: F401
from map_server.saver import SaverError, pgm_bytes, yaml_text, save_map, check_thresholds  # noqa: F401
