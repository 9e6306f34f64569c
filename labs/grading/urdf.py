"""The robot model of a URDF text as plain data, for the graders of labs 3 and 4 (no rospy).

`parse_urdf` reads links (collisions with their origin's rpy, visual, inertial) and joints
(type, parent, child, mimic); `body_link` and `body_size` find the robot's body and its box.
"""
import math
import xml.etree.ElementTree as ET


class ModelError(Exception):
    """The URDF text cannot be analysed; the message says why (one line)."""


def _floats(text, n, what):
    try:
        v = [float(x) for x in (text or '').split()]
    except ValueError:
        raise ModelError('%s: %r is not %d numbers' % (what, text, n))
    if len(v) != n:
        raise ModelError('%s: %r is not %d numbers' % (what, text, n))
    return v


def _geometry(el, what):
    g = el.find('geometry')
    if g is None or not len(g):
        return None
    shape = g[0]
    t = shape.tag
    if t == 'box':
        return ('box', _floats(shape.get('size'), 3, what + ' box size'))
    if t == 'cylinder':
        return ('cylinder', [float(shape.get('radius', 'nan')), float(shape.get('length', 'nan'))])
    if t == 'sphere':
        return ('sphere', [float(shape.get('radius', 'nan'))])
    return (t, [])


def _rpy(el):
    o = el.find('origin')
    if o is None or not o.get('rpy'):
        return (0.0, 0.0, 0.0)
    return tuple(_floats(o.get('rpy'), 3, 'origin rpy'))


def parse_urdf(text):
    """{'name', 'links': {name: {...}}, 'joints': {name: {...}}}; ModelError when unusable."""
    try:
        root = ET.fromstring(text)
    except ET.ParseError as e:
        raise ModelError('not XML: %s' % e)
    if root.tag != 'robot':
        raise ModelError('the root element is <%s>, not <robot>' % root.tag)
    links, joints = {}, {}
    for l in root.findall('link'):
        name = l.get('name')
        what = 'link %s' % name
        cols = []
        for c in l.findall('collision'):
            g = _geometry(c, what + ' collision')
            if g:
                cols.append((g[0], g[1], _rpy(c)))
        inertial = None
        i = l.find('inertial')
        if i is not None:
            m = i.find('mass')
            t = i.find('inertia')
            try:
                mass = float(m.get('value')) if m is not None else None
                tensor = {k: float(t.get(k, 'nan')) for k in ('ixx', 'iyy', 'izz')} if t is not None else None
            except ValueError:
                raise ModelError('%s: inertial values are not numbers' % what)
            inertial = {'mass': mass, 'inertia': tensor}
        links[name] = {'collisions': cols, 'visual': l.find('visual') is not None, 'inertial': inertial}
    for j in root.findall('joint'):
        p, c = j.find('parent'), j.find('child')
        joints[j.get('name')] = {'type': j.get('type'), 'parent': p.get('link') if p is not None else None,
                                 'child': c.get('link') if c is not None else None,
                                 'mimic': j.find('mimic') is not None}
    if not links:
        raise ModelError('the model has no <link>')
    return {'name': root.get('name'), 'links': links, 'joints': joints}


def root_link(model):
    kids = {j['child'] for j in model['joints'].values()}
    roots = [l for l in model['links'] if l not in kids]
    if len(roots) != 1:
        raise ModelError('the links form %d trees (roots: %s), one tree expected' % (len(roots), ', '.join(sorted(roots))))
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
