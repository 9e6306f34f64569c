#!/usr/bin/env python3
"""Generate ode_sim's model library (models/NAME/{model.config,model.sdf,meshes/*.stl} and
models/README.md) from the definitions in model_objects.py (furniture) and model_rooms.py
(rooms). Deterministic: running it again gives
byte-identical files.

    python3 scripts/make_models.py            # writes into the package's models/
    python3 scripts/make_models.py --out DIR  # writes somewhere else (tests compare)

Every object's origin is at the centre of its footprint on the floor (z = 0 at its bottom),
its front faces +x. Sizes in metres, masses in kg.
"""
import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
PKG = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(PKG, 'src'))
sys.path.insert(0, HERE)

from ode_sim.description import meshgen as mg  # noqa: E402
from model_objects import objects  # noqa: E402
from model_rooms import MAZE, OFFICE_DOORWAYS, WALL_T, rooms  # noqa: E402

SDF_VERSION = '1.6'
AUTHOR = 'ode_sim authors'


def fmt(v, digits=6):
    s = ('%.*f' % (digits, v)).rstrip('0').rstrip('.')
    return '0' if s in ('-0', '') else s


def vec(values, digits=6):
    return ' '.join(fmt(v, digits) for v in values)


def model_config(name, description):
    return ('<?xml version="1.0"?>\n<model>\n  <name>%s</name>\n  <version>1.0</version>\n'
            '  <sdf version="%s">model.sdf</sdf>\n  <author>\n    <name>%s</name>\n'
            '    <email></email>\n  </author>\n  <description>\n    %s\n  </description>\n'
            '</model>\n' % (name, SDF_VERSION, AUTHOR, description))


def material(rgba, indent):
    pad = ' ' * indent
    spec = (0.1, 0.1, 0.1, 1.0)
    return ('%s<material>\n%s  <ambient>%s</ambient>\n%s  <diffuse>%s</diffuse>\n'
            '%s  <specular>%s</specular>\n%s</material>\n'
            % (pad, pad, vec(rgba, 3), pad, vec(rgba, 3), pad, vec(spec, 3), pad))


def geometry_xml(kind, dims, indent, uri=None):
    pad = ' ' * indent
    if kind == 'box':
        inner = '<box><size>%s</size></box>' % vec(dims)
    elif kind == 'cylinder':
        inner = '<cylinder><radius>%s</radius><length>%s</length></cylinder>' % (
            fmt(dims[0]), fmt(dims[1]))
    elif kind == 'sphere':
        inner = '<sphere><radius>%s</radius></sphere>' % fmt(dims[0])
    elif kind == 'mesh':
        inner = '<mesh><uri>%s</uri></mesh>' % uri
    else:
        raise ValueError(kind)
    return '%s<geometry>\n%s  %s\n%s</geometry>\n' % (pad, pad, inner, pad)


def object_sdf(o):
    com, inertia = mg.composite_inertia(o.mass, [c[1:] for c in o.collisions])
    lines = ['<?xml version="1.0"?>\n<sdf version="%s">\n' % SDF_VERSION,
             '  <model name="%s">\n' % o.name,
             '    <static>%s</static>\n' % ('true' if o.static else 'false'),
             '    <link name="link">\n',
             '      <inertial>\n        <pose>%s 0 0 0</pose>\n        <mass>%s</mass>\n'
             % (vec(com, 4), fmt(o.mass)),
             '        <inertia>\n']
    for tag, (a, b) in (('ixx', (0, 0)), ('ixy', (0, 1)), ('ixz', (0, 2)), ('iyy', (1, 1)),
                        ('iyz', (1, 2)), ('izz', (2, 2))):
        lines.append('          <%s>%s</%s>\n' % (tag, fmt(inertia[a, b], 5), tag))
    lines.append('        </inertia>\n      </inertial>\n')
    for name, kind, dims, xyz, rpy, _ in o.collisions:
        lines.append('      <collision name="%s">\n        <pose>%s %s</pose>\n'
                     % (name, vec(xyz), vec(rpy)))
        lines.append(geometry_xml(kind, dims, 8))
        lines.append('      </collision>\n')
    for name, rgba, _ in o.visuals:
        lines.append('      <visual name="%s">\n' % name)
        lines.append(geometry_xml('mesh', None, 8, o.mesh_uri(name)))
        lines.append(material(rgba, 8))
        lines.append('      </visual>\n')
    lines.append('    </link>\n  </model>\n</sdf>\n')
    return ''.join(lines)


def room_sdf(room):
    lines = ['<?xml version="1.0"?>\n<sdf version="%s">\n' % SDF_VERSION,
             '  <model name="%s">\n    <static>true</static>\n    <link name="walls">\n'
             % room.name]
    for name, size, xyz in room.boxes():
        for tag in ('collision', 'visual'):
            lines.append('      <%s name="%s">\n        <pose>%s 0 0 0</pose>\n'
                         % (tag, name, vec(xyz)))
            lines.append(geometry_xml('box', size, 8))
            if tag == 'visual':
                lines.append(material(room.color, 8))
            lines.append('      </%s>\n' % tag)
    lines.append('    </link>\n  </model>\n</sdf>\n')
    return ''.join(lines)


GROUND_PLANE_SDF = '''<?xml version="1.0"?>
<sdf version="1.6">
  <model name="ground_plane">
    <static>true</static>
    <link name="link">
      <collision name="collision">
        <geometry>
          <plane><normal>0 0 1</normal><size>100 100</size></plane>
        </geometry>
        <surface>
          <friction>
            <ode><mu>100</mu><mu2>50</mu2></ode>
          </friction>
        </surface>
      </collision>
      <visual name="visual">
        <cast_shadows>false</cast_shadows>
        <geometry>
          <plane><normal>0 0 1</normal><size>100 100</size></plane>
        </geometry>
        <material>
          <ambient>0.5 0.5 0.5 1</ambient>
          <diffuse>0.5 0.5 0.5 1</diffuse>
          <specular>0.1 0.1 0.1 1</specular>
        </material>
      </visual>
    </link>
  </model>
</sdf>
'''

SUN_SDF = '''<?xml version="1.0"?>
<sdf version="1.6">
  <light type="directional" name="sun">
    <cast_shadows>true</cast_shadows>
    <pose>0 0 10 0 0 0</pose>
    <diffuse>0.8 0.8 0.8 1</diffuse>
    <specular>0.2 0.2 0.2 1</specular>
    <attenuation>
      <range>1000</range>
      <constant>0.9</constant>
      <linear>0.01</linear>
      <quadratic>0.001</quadratic>
    </attenuation>
    <direction>-0.5 0.1 -0.9</direction>
  </light>
</sdf>
'''


def write(path, data):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    mode = 'wb' if isinstance(data, bytes) else 'w'
    with open(path, mode) as f:
        f.write(data)


def readme(objs, rms):
    lines = [
        '# ode_sim model library\n\n',
        'Models of our own making, in the Gazebo layout (`NAME/model.config`, `NAME/model.sdf`,\n',
        'SDF %s, `NAME/meshes/*.stl`), found by `model://NAME` in worlds. Everything here is\n'
        % SDF_VERSION,
        'generated by `scripts/make_models.py`: do not edit by hand, change the script and run\n\n',
        '    python3 scripts/make_models.py            # from catkin_ws/src/sim/ode_sim\n\n',
        'The output is deterministic (regenerating gives byte-identical files; the tests check\n',
        'it). Each object\'s origin is the centre of its footprint on the floor, its front faces\n',
        '+x. Visuals are binary STL meshes, one per colour (`<material>` ambient/diffuse);\n',
        'collisions are a few boxes/cylinders/spheres approximating the shape (cheaper contacts\n',
        'and ray casts), which also give the inertia (mass spread by volume).\n\n',
        '## Environment\n\n',
        '| model | description |\n|---|---|\n',
        '| `ground_plane` | static plane, friction mu 100 / mu2 50, grey 100 x 100 m visual |\n',
        '| `sun` | directional light at 0 0 10, direction -0.5 0.1 -0.9, casts shadows |\n\n',
        '## Objects\n\n',
        '| model | size x × y × z (m) | mass (kg) | triangles | description |\n',
        '|---|---|---|---|---|\n']
    for o in objs:
        tris = sum(len(p) for _, _, p in o.visuals)
        lines.append('| `%s` | %s | %s%s | %d | %s |\n' % (
            o.name, ' × '.join(fmt(s, 3) for s in o.size), fmt(o.mass),
            ' (static)' if o.static else '', tris, o.title))
    lines += ['\n## Rooms (static, walls %s m thick, box collisions)\n\n' % fmt(WALL_T),
              '| model | walls | description |\n|---|---|---|\n']
    for r in rms:
        lines.append('| `%s` | %d | %s |\n' % (r.name, len(r.walls), r.title))
    lines += ['\nOffice doorways (centre x y in the model frame, width):\n\n']
    for name, (x, y), axis, w in OFFICE_DOORWAYS:
        lines.append('- `%s`: %s %s, %s m, passage along %s\n'
                     % (name, fmt(x), fmt(y), fmt(w), axis))
    lines += ['\nThe maze layout (`#` wall, north up, entrance and exit on the middle row):\n\n']
    lines += ['    %s\n' % row for row in MAZE]
    lines += ['\nThe maze frame\'s origin is the middle of the entrance opening; cells span '
              'x 0..5,\n',
              'y -2.5..2.5.\n\n',
              '## Worlds (`../worlds/`)\n\n',
              '| world | contents |\n|---|---|\n',
              '| `empty.world` | sun + ground_plane, Gazebo\'s default ODE physics '
              '(as Gazebo\'s) |\n',
              '| `empty_room.world` | `empty_room` centred on the origin |\n',
              '| `office.world` | `office` + 13 pieces of furniture; the origin is in room B, '
              '1 m clear |\n',
              '| `maze.world` | `maze` at x = 1: the entrance 1 m ahead of the origin, the exit at '
              'x = 6 |\n',
              '| `objects.world` | 5 objects 2-5 m ahead (+x) of the origin, for camera/lidar '
              'demos |\n',
              '| `textbook.world` | practical work 4 (SDF 1.4): scene, quick solver 150 iters, '
              'SOR 1.4, CFM 1e-5 |\n']
    return ''.join(lines)


def generate(out):
    objs, rms = objects(), rooms()
    write(os.path.join(out, 'ground_plane', 'model.config'),
          model_config('ground_plane', 'A large static ground plane (100 x 100 m).'))
    write(os.path.join(out, 'ground_plane', 'model.sdf'), GROUND_PLANE_SDF)
    write(os.path.join(out, 'sun', 'model.config'),
          model_config('sun', 'A directional light, as the sun.'))
    write(os.path.join(out, 'sun', 'model.sdf'), SUN_SDF)
    for o in objs:
        d = os.path.join(out, o.name)
        write(os.path.join(d, 'model.config'), model_config(o.name, '%s; %s m; %s kg.' % (
            o.title, ' x '.join(fmt(s, 3) for s in o.size), fmt(o.mass))))
        write(os.path.join(d, 'model.sdf'), object_sdf(o))
        for name, _, part in o.visuals:
            write(os.path.join(d, 'meshes', name + '.stl'),
                  mg.stl_bytes(part, '%s/%s' % (o.name, name)))
    for r in rms:
        d = os.path.join(out, r.name)
        write(os.path.join(d, 'model.config'), model_config(r.name, r.title + '.'))
        write(os.path.join(d, 'model.sdf'), room_sdf(r))
    write(os.path.join(out, 'README.md'), readme(objs, rms))
    return objs, rms


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--out', default=os.path.join(PKG, 'models'),
                    help='directory to write the models into (default: the package\'s models/)')
    args = ap.parse_args(argv)
    objs, rms = generate(args.out)
    print('wrote %d objects and %d rooms into %s' % (len(objs), len(rms), args.out))


if __name__ == '__main__':
    main()
