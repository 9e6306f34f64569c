#!/usr/bin/env python3
"""Check a robot model for RViz and the simulator: check_urdf plus every link with collision
and a physically valid inertial, one tree, axes on moving joints, materials, meshes.

    rosrun my_robot_model check_model.py FILE.urdf|FILE.xacro [--root-frame base_footprint] [name:=value ...]
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), 'src'))
from my_robot_model import model_check  # noqa: E402


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('file', help='a URDF, or a xacro file (expanded with rosrun xacro xacro)')
    ap.add_argument('--root-frame', action='append', default=None,
                    help='a root link that may be a bare frame (default: base_footprint)')
    ap.add_argument('mappings', nargs='*', help='xacro arguments name:=value')
    args = ap.parse_args(argv)
    prog = 'check_model.py'
    if not os.path.isfile(args.file):
        print('%s: %s: no such file' % (prog, args.file), file=sys.stderr)
        return 2
    try:
        if args.file.endswith('.xacro'):
            text = model_check.expand_xacro(args.file, args=args.mappings)
        else:
            with open(args.file) as f:
                text = f.read()
        rc, out = model_check.check_urdf(text)
        found = [] if rc == 0 else ['check_urdf: ' + (out.strip().splitlines() or ['failed'])[-1]]
        found += model_check.problems(text, tuple(args.root_frame or ('base_footprint',)),
                                      model_check.rospack_resolver())
    except (model_check.ModelError, OSError) as e:
        print('%s: %s: %s' % (prog, args.file, e), file=sys.stderr)
        return 2
    for p in found:
        print('%s: %s' % (args.file, p))
    if found:
        return 1
    model = model_check.parse(text)
    print('%s: OK: robot %s, %d links, %d joints (%d moving), root %s'
          % (args.file, model.name, len(model.links), len(model.joints),
             len(model.moving_joints()), model.root()))
    return 0


if __name__ == '__main__':
    sys.exit(main())
