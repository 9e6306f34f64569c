#!/usr/bin/python3
"""Writes maps/office.pgm + maps/office.yaml, the ground-truth map of the office world: its
collision shapes (with the models of ode_sim's library) cut at the RPLidar's scan plane
(0.12 m), the floor inside the outer walls free, the rest unknown. Used by the navigation
tests, bench/amcl and the main demo's map-quality figures.

    rosrun space_scanner_simulation make_office_map.py [OUT_BASE]"""
import os
import sys

import rospkg

from course_runtime import world_map

SCAN_HEIGHT = 0.12         # m above the floor: chassi_bot's laser frame
RESOLUTION = 0.05
ORIGIN = (-6.5, -4.5)
SIZE = (13.0, 9.0)
FREE_BOX = (-6.0, -4.0, 6.0, 4.0)


def main(argv):
    pkg = rospkg.RosPack().get_path('space_scanner_simulation')
    base = argv[1] if len(argv) > 1 else os.path.join(pkg, 'maps', 'office')
    shapes = world_map.world_collisions(os.path.join(pkg, 'worlds', 'office.world'))
    img = world_map.rasterize_slice(shapes, SCAN_HEIGHT, ORIGIN, SIZE, RESOLUTION, free_box=FREE_BOX)
    world_map.write_map_files(img, base, ORIGIN, RESOLUTION,
                              'office.world at z %.2f m (make_office_map.py)' % SCAN_HEIGHT)
    print('%s.pgm: %d x %d, %d occupied cells' % (base, img.shape[1], img.shape[0], int((img == 0).sum())))


if __name__ == '__main__':
    main(sys.argv)
