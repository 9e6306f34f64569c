"""Lab 3's reading of a parsed URDF (grading.urdf): body, wheels, manipulator chain, counted
links, links lacking collision or inertial (no rospy). The definitions: grading.lab3.
"""
import xml.etree.ElementTree as ET

from grading.urdf import body_link, root_link

MOVABLE = ('revolute', 'continuous', 'prismatic', 'floating', 'planar')
CODE = {'revolute': 'R', 'prismatic': 'P', 'continuous': 'C', 'fixed': 'F',
        'floating': 'FL', 'planar': 'PL'}


def xacro_args(path):
    """Names of the <xacro:arg> declared in a xacro file (empty if unreadable)."""
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError):
        return []
    return [el.get('name') for el in root.iter() if isinstance(el.tag, str)
            and el.tag.split('}')[-1] == 'arg' and el.tag.startswith('{') and el.get('name')]


def _children(model):
    ch = {}
    for n, j in model['joints'].items():
        ch.setdefault(j['parent'], []).append(n)
    return ch


def subtree(model, link, ch=None):
    ch = ch if ch is not None else _children(model)
    out, todo = [], [link]
    while todo:
        l = todo.pop()
        out.append(l)
        todo += [model['joints'][j]['child'] for j in ch.get(l, [])]
    return out


def rigid_group(model, body):
    """The body and every link connected to it through fixed joints only (either direction)."""
    group, todo = {body}, [body]
    while todo:
        l = todo.pop()
        for j in model['joints'].values():
            if j['type'] != 'fixed':
                continue
            for a, b in ((j['parent'], j['child']), (j['child'], j['parent'])):
                if a == l and b not in group:
                    group.add(b)
                    todo.append(b)
    return group


def analyse(model):
    """Body, wheels, arm chain and counted links of a parsed model."""
    root = root_link(model)
    body = body_link(model)
    group = rigid_group(model, body)
    ch = _children(model)
    wheels = []
    for n, j in sorted(model['joints'].items()):
        shapes = [c[0] for c in model['links'][j['child']]['collisions']]
        if j['parent'] not in group or j['child'] == body:
            continue
        if j['type'] == 'fixed' and 'sphere' not in shapes:
            continue
        sub = subtree(model, j['child'], ch)
        movable_below = [k for k, jj in model['joints'].items()
                         if jj['parent'] in sub and jj['type'] in MOVABLE]
        if movable_below:
            continue
        if 'sphere' in shapes and j['type'] in ('fixed', 'continuous'):
            wheels.append((n, 'S'))
        elif 'cylinder' in shapes and j['type'] in MOVABLE:
            wheels.append((n, CODE.get(j['type'], j['type'])))
    wheel_names = {n for n, _ in wheels}
    wheel_links = set()
    for n in wheel_names:
        wheel_links.update(subtree(model, model['joints'][n]['child'], ch))
    arm = [n for n, j in model['joints'].items()
           if j['type'] in MOVABLE and n not in wheel_names and not j['mimic']]
    depth = {}
    parent_joint = {j['child']: n for n, j in model['joints'].items()}

    def path(link):
        out = []
        while link in parent_joint:
            out.append(parent_joint[link])
            link = model['joints'][parent_joint[link]]['parent']
        return out[::-1]
    for n in arm:
        depth[n] = len(path(model['joints'][n]['child']))
    arm.sort(key=lambda n: (depth[n], n))
    branch = None
    for a, b in zip(arm, arm[1:]):
        if a not in path(model['joints'][b]['child']):
            branch = (a, b)
            break
    counted = sorted(l for l in model['links'] if l not in wheel_links)
    return {'root': root, 'body': body, 'group': sorted(group), 'wheels': wheels, 'arm': arm,
            'arm_codes': ''.join(CODE.get(model['joints'][n]['type'], '?') for n in arm),
            'branch': branch, 'links': counted, 'wheel_links': sorted(wheel_links)}


def link_problems(model):
    """['link: what is missing'] for links without collision or a positive-mass inertial.
    Pure frames (no visual and no collision, e.g. base_footprint) are exempt."""
    bad = []
    for name, l in sorted(model['links'].items()):
        if not l['collisions'] and not l['visual']:
            continue
        miss = []
        if not l['collisions']:
            miss.append('no <collision>')
        i = l['inertial']
        if i is None:
            miss.append('no <inertial>')
        elif i['mass'] is None or not i['mass'] > 0:
            miss.append('mass %s' % ('missing' if i['mass'] is None else '%g' % i['mass']))
        elif i['inertia'] is None:
            miss.append('no <inertia>')
        elif not all(v > 0 for v in i['inertia'].values()):
            miss.append('inertia ixx/iyy/izz not positive')
        if miss:
            bad.append('%s: %s' % (name, ', '.join(miss)))
    return bad
