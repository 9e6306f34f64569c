#!/usr/bin/env python3
"""Writes the image loader's test images (run from anywhere; the files are committed):
testmap.png / testmap.bmp - the 10 x 10 map of navigation's map_server tests (black = occupied);
spectrum.png - an RGBA ramp (row 0 opaque grey 0..255, row 1 the same half transparent, row 2
fully transparent, row 3 coloured), and spectrum_<mode>.txt: what map_io.py makes of it (the
gtest reads the same image through the C++ loader and must get the same cells)."""
import os
import sys

import numpy as np
from PIL import Image

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, '..', 'src'))
from map_server.map_io import _read_pixels, pixels_to_cells  # noqa: E402

# the map, bottom row first (as an OccupancyGrid's data)
TESTMAP = [[0] * 10,
           [100, 100, 100, 100, 0, 0, 100, 100, 100, 0],
           [100, 100, 100, 100, 0, 0, 100, 100, 100, 0],
           [100] + [0] * 9,
           [100] + [0] * 9,
           [100, 0, 0, 0, 0, 0, 100, 100, 0, 0],
           [100, 0, 0, 0, 0, 0, 100, 100, 0, 0],
           [100, 0, 0, 0, 0, 0, 100, 100, 0, 0],
           [100, 0, 0, 0, 0, 0, 100, 100, 0, 0],
           [100] + [0] * 9]
# (mode, negate): thresholds 0.65 / 0.196
CASES = {'trinary': ('trinary', False), 'scale': ('scale', False), 'raw': ('raw', False),
         'negate': ('trinary', True)}


def main():
    img = np.where(np.array(TESTMAP[::-1]) == 100, 0, 255).astype(np.uint8)   # top row first
    Image.fromarray(img, 'L').save(os.path.join(HERE, 'testmap.png'))
    Image.fromarray(img, 'L').convert('RGB').save(os.path.join(HERE, 'testmap.bmp'))
    ramp = np.linspace(0, 255, 32).round().astype(np.uint8)
    rgba = np.zeros((4, 32, 4), dtype=np.uint8)
    for row, alpha in enumerate((255, 128, 0)):
        rgba[row, :, :3] = ramp[:, None]
        rgba[row, :, 3] = alpha
    rgba[3, :, 0], rgba[3, :, 1], rgba[3, :, 2], rgba[3, :, 3] = ramp, 255 - ramp, 90, 255
    path = os.path.join(HERE, 'spectrum.png')
    Image.fromarray(rgba, 'RGBA').save(path)
    pixels, has_alpha = _read_pixels(path)
    for name, (mode, negate) in CASES.items():
        cells = pixels_to_cells(pixels, has_alpha, negate, 0.65, 0.196, mode)
        np.savetxt(os.path.join(HERE, 'spectrum_%s.txt' % name), cells, fmt='%d')


if __name__ == '__main__':
    main()
