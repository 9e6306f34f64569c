"""The robot model of a URDF text as plain data, for the graders of labs 3 and 4 (no rospy).

`parse_urdf` gives the graders' view of the tree that ode_sim.description.urdf_tree (the one
URDF reader of the repository) reads: links (collisions with their origin's rpy, visual,
inertial) and joints (type, parent, child, mimic); `body_link` and `body_size` find the robot's
body and its box.
"""
import math

from ode_sim.description import urdf_tree


class ModelError(Exception):
    """The URDF text cannot be analysed; the message says why (one line)."""


def _numbers(text, n, what):
    v = urdf_tree.floats(text)
    if v is None or len(v) != n:
        raise ModelError('%s: %r is not %s' % (what, text, 'a number' if n == 1 else '%d numbers' % n))
    return v


def _length(shape, attr, what):
    """A cylinder's or sphere's radius/length: nan when left out."""
    if shape.attrs.get(attr) is None:
        return float('nan')
    return _numbers(shape.attrs[attr], 1, '%s %s %s' % (what, shape.kind, attr))[0]


def _collision(shape, what):
    """(kind, dimensions, rpy) of a urdf_tree.Shape, or None when it has no geometry."""
    if not shape.shapes:
        return None
    if shape.kind == 'box':
        dims = _numbers(shape.attrs.get('size'), 3, what + ' box size')
    elif shape.kind == 'cylinder':
        dims = [_length(shape, 'radius', what), _length(shape, 'length', what)]
    elif shape.kind == 'sphere':
        dims = [_length(shape, 'radius', what)]
    else:
        dims = []
    if shape.origin.rpy is None:
        raise ModelError('origin rpy: %r is not 3 numbers' % shape.origin.el.get('rpy'))
    return (shape.kind, dims, tuple(shape.origin.rpy))


def _inertial(inertial, what):
    """{'mass', 'inertia': {ixx, iyy, izz}} of a urdf_tree.Inertial (inertia values left out:
    nan; no <mass>, no <inertia>: None)."""
    if inertial is None:
        return None
    mass = tensor = None
    if inertial.mass_el is not None:
        mass = inertial.mass
    if inertial.inertia_el is not None:
        tensor = {k: float('nan') if inertial.inertia_el.get(k) is None else inertial.inertia[k]
                  for k in ('ixx', 'iyy', 'izz')}
    if (inertial.mass_el is not None and mass is None) or None in (tensor or {}).values():
        raise ModelError('%s: inertial values are not numbers' % what)
    return {'mass': mass, 'inertia': tensor}


def parse_urdf(text):
    """{'name', 'links': {name: {...}}, 'joints': {name: {...}}}; ModelError when unusable."""
    try:
        tree = urdf_tree.read_urdf(text)
    except urdf_tree.NotUrdf as e:
        raise ModelError(str(e))
    links, joints = {}, {}
    for name, l in tree.links.items():
        what = 'link %s' % name
        cols = [c for c in (_collision(c, what + ' collision') for c in l.collisions) if c]
        links[name] = {'collisions': cols, 'visual': bool(l.visuals), 'inertial': _inertial(l.inertial, what)}
    for name, j in tree.joints.items():
        joints[name] = {'type': j.type, 'parent': j.parent, 'child': j.child, 'mimic': j.mimic_el is not None}
    if not links:
        raise ModelError('the model has no <link>')
    return {'name': tree.name, 'links': links, 'joints': joints}


def root_link(model):
    kids = {j['child'] for j in model['joints'].values()}
    roots = [l for l in model['links'] if l not in kids]
    if len(roots) != 1:
        raise ModelError('the links form %d trees (roots: %s), one tree expected'
                         % (len(roots), ', '.join(sorted(roots))))
    return roots[0]


def body_link(model):
    return 'base_link' if 'base_link' in model['links'] else root_link(model)


def _rot(rpy):
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr]]


def body_size(model, body):
    """(L, W, H) in mm: the largest box collision of the body link, as extents along the
    link's x, y, z (a rotated origin is taken into account); ModelError if there is none."""
    boxes = [(c[1], c[2]) for c in model['links'][body]['collisions'] if c[0] == 'box']
    if not boxes:
        shapes = ', '.join(c[0] for c in model['links'][body]['collisions']) or 'no collision'
        raise ModelError('the body link %s has no box collision (%s)' % (body, shapes))
    size, rpy = max(boxes, key=lambda b: b[0][0] * b[0][1] * b[0][2])
    R = _rot(rpy)
    return [1000.0 * sum(abs(R[i][k]) * size[k] for k in range(3)) for i in range(3)]
