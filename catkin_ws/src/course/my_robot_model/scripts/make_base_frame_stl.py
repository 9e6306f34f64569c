#!/usr/bin/env python3
"""Write models/base_frame.stl (the base mesh of diff_robot_model) with numpy-stl.

    rosrun my_robot_model make_base_frame_stl.py [OUTPUT]   (default: the package's models/)
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), 'src'))
from my_robot_model import base_frame  # noqa: E402


def main(argv=None):
    default = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                           'models', 'base_frame.stl')
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('output', nargs='?', default=default, help='STL file to write (%(default)s)')
    for name in ('length', 'width', 'height', 'chamfer', 'wall', 'floor'):
        ap.add_argument('--' + name, type=float, default=getattr(base_frame, name.upper()),
                        help='metres (default %(default)s)')
    args = ap.parse_args(argv)
    dims = {k: getattr(args, k) for k in ('length', 'width', 'height', 'chamfer', 'wall', 'floor')}
    try:
        data = base_frame.stl_bytes(**dims)
        with open(args.output, 'wb') as f:
            f.write(data)
    except (ValueError, OSError) as e:
        print('make_base_frame_stl.py: %s' % e, file=sys.stderr)
        return 1
    print('wrote %s (%d triangles, %d bytes)' % (args.output, (len(data) - 84) // 50, len(data)))
    return 0


if __name__ == '__main__':
    sys.exit(main())
