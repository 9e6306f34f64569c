"""map_saver's file format (map_saver.cpp): a binary PGM and the YAML beside it."""
import math

import numpy as np

from map_server.grid import Grid  # noqa: F401  (type in docs)

DEFAULT_OCC = 65
DEFAULT_FREE = 25


class SaverError(Exception):
    """Bad map_saver arguments; str(e) is the original's message."""


def check_thresholds(occ, free):
    if not 1 <= occ <= 100:
        raise SaverError('threshold_occupied must be between 1 and 100')
    if not 0 <= free <= 100:
        raise SaverError('threshold_free must be between 0 and 100')
    if occ <= free:
        raise SaverError('threshold_free must be smaller than threshold_occupied')


def pgm_bytes(grid, occ=DEFAULT_OCC, free=DEFAULT_FREE):
    """Grid -> the bytes of map_saver's P5 PGM: free (0..free) 254, occupied (>= occ) 0, else 205;
    top row first."""
    data = np.asarray(grid.data, dtype=np.int8).reshape(grid.height, grid.width)
    img = np.full(data.shape, 205, dtype=np.uint8)
    img[(data >= 0) & (data <= free)] = 254
    img[data >= occ] = 0
    header = '''P5
# CREATOR: map_saver.cpp %.3f m/pix
%d %d
255
''' % (grid.resolution, grid.width, grid.height)
    return header.encode('ascii') + img[::-1].tobytes()


def yaml_text(image_name, resolution, origin):
    """The map YAML map_saver writes (thresholds fixed at 0.65 / 0.196, as the original)."""
    x, y, yaw = origin
    if math.isnan(yaw):
        yaw = 0.0
    return ('image: %s\nresolution: %f\norigin: [%f, %f, %f]\nnegate: 0\noccupied_thresh: 0.65\n'
            'free_thresh: 0.196\n\n' % (image_name, resolution, x, y, yaw))


def save_map(grid, mapname, occ=DEFAULT_OCC, free=DEFAULT_FREE, log=print):
    """Write <mapname>.pgm and <mapname>.yaml; log gets map_saver's progress lines."""
    pgm = mapname + '.pgm'
    log('Writing map occupancy data to %s' % pgm)
    with open(pgm, 'wb') as f:
        f.write(pgm_bytes(grid, occ, free))
    yml = mapname + '.yaml'
    log('Writing map occupancy data to %s' % yml)
    with open(yml, 'w') as f:
        f.write(yaml_text(pgm, grid.resolution, grid.origin))
    return pgm, yml
