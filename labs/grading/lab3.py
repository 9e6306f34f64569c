"""Lab 3 rules: a mobile base with a manipulator in urdf/my_robots_super_model.xacro, shown in RViz.

Pure logic: the URDF analysis (body, wheels, manipulator chain, links, inertials), the RViz
config check and `evaluate(obs)` that turns an observation (grading.observe.Lab3Observer) into
the seven criteria. No rospy here.

Definitions (also in labs/lab3/README.md):
  body      the link named `base_link`, else the root link of the tree;
  rigid body group  the body and every link joined to it through fixed joints only;
  wheel     a joint whose parent is in the rigid body group, whose child subtree has no movable
            joint, and whose child link has a cylinder collision on a movable joint (a wheel) or
            a sphere collision on any joint (a caster, code S);
  arm       every other movable joint (mimic joints aside), which must form one serial chain;
            read from the body outwards;
  links     the table's "Кол-во звеньев" passes in either reading: every <link> of the URDF
            (the book's count: a URDF is links joined by joints, wheels and base included) or
            every link except wheel/caster links and their subtrees (the only reading in which
            variants 1, 3, 5 and 6 can be built).
"""
import math
import os
import xml.etree.ElementTree as ET

import yaml

from grading.common import Criterion, reason, variant

PACKAGE = 'my_firts_robot_model'
GRADER_PKG = 'lab3_grader'
MODEL = 'urdf/my_robots_super_model.xacro'
LAUNCH = 'lab3_setup.launch'
DEFAULT_TIMEOUT = 360.0
SIZE_TOL = 5.0          # mm, per dimension of the body box
LAUNCH_LIMIT = 120.0    # s from roslaunch until every piece of criterion 7 is seen (RViz on a loaded machine)
STEP_TIMEOUT = 60.0     # s, xacro and check_urdf each
RVIZ_SETTLE = 3.0       # s RViz must keep running after everything was seen
MOVABLE = ('revolute', 'continuous', 'prismatic', 'floating', 'planar')
CODE = {'revolute': 'R', 'prismatic': 'P', 'continuous': 'C', 'fixed': 'F',
        'floating': 'FL', 'planar': 'PL'}
VARIANT_ARGS = ('isu', 'variant')
RVIZ_NEEDED = (('rviz/RobotModel', 'RobotModel'), ('rviz/TF', 'TF'))

CRITERIA = [
    ('1', 'urdf/my_robots_super_model.xacro раскрывается xacro и проходит check_urdf',
     'urdf/my_robots_super_model.xacro expands with xacro and passes check_urdf'),
    ('2', 'Число звеньев по варианту (все звенья URDF или без колёс)',
     'Number of links matches the variant (every URDF link, or wheels aside)'),
    ('3', 'Типы шарниров манипулятора по варианту', 'Manipulator joint types match the variant'),
    ('4', 'Колёсные шарниры (число и тип) по варианту', 'Wheel joints (number and type) match the variant'),
    ('5', 'Габариты корпуса по варианту (±5 мм)', 'Body size matches the variant (±5 mm)'),
    ('6', 'У каждого звена есть collision и inertial с массой > 0',
     'Every link has collision and inertial with mass > 0'),
    ('7', 'lab3_setup.launch: robot_description, robot_state_publisher, joint_state_publisher, '
          'RViz с RobotModel и TF; TF всех звеньев',
     'lab3_setup.launch: robot_description, robot_state_publisher, joint_state_publisher, '
     'RViz with RobotModel and TF; TF of every link'),
]


class ModelError(Exception):
    """The URDF text cannot be analysed; the message says why (one line)."""


def spec(isu):
    v = variant('lab3', isu)
    return {'links': int(v['links']), 'arm': str(v['arm']), 'wheels': str(v['wheels']),
            'body': [float(x) for x in v['body']]}


# --- files of the package ---------------------------------------------------------------

def find_file(pkg_dir, rel):
    p = os.path.join(pkg_dir, rel)
    return p if os.path.isfile(p) else None


def find_launch(pkg_dir):
    for d, dirs, files in os.walk(pkg_dir):
        dirs[:] = sorted(x for x in dirs if not x.startswith('.') and x not in ('build', 'devel'))
        if LAUNCH in files:
            return os.path.join(d, LAUNCH)
    return None


def xacro_args(path):
    """Names of the <xacro:arg> declared in a xacro file (empty if unreadable)."""
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError):
        return []
    return [el.get('name') for el in root.iter() if isinstance(el.tag, str)
            and el.tag.split('}')[-1] == 'arg' and el.tag.startswith('{') and el.get('name')]


def launch_args(path):
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError):
        return []
    return [a.get('name') for a in root.findall('arg') if a.get('name')]


def variant_args(declared, isu):
    """`name:=value` for the variant args (isu, variant) that a file declares."""
    vals = {'isu': isu, 'variant': isu[-1]}
    return ['%s:=%s' % (n, vals[n]) for n in VARIANT_ARGS if n in declared]


# --- URDF model ---------------------------------------------------------------------------

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


def _children(model):
    ch = {}
    for n, j in model['joints'].items():
        ch.setdefault(j['parent'], []).append(n)
    return ch


def root_link(model):
    kids = {j['child'] for j in model['joints'].values()}
    roots = [l for l in model['links'] if l not in kids]
    if len(roots) != 1:
        raise ModelError('the links form %d trees (roots: %s), one tree expected' % (len(roots), ', '.join(sorted(roots))))
    return roots[0]


def subtree(model, link, ch=None):
    ch = ch if ch is not None else _children(model)
    out, todo = [], [link]
    while todo:
        l = todo.pop()
        out.append(l)
        todo += [model['joints'][j]['child'] for j in ch.get(l, [])]
    return out


def body_link(model):
    return 'base_link' if 'base_link' in model['links'] else root_link(model)


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


# --- RViz config --------------------------------------------------------------------------

def rviz_displays(text):
    """(display classes, fixed frame) of an .rviz YAML config; ModelError if unreadable."""
    try:
        cfg = yaml.safe_load(text)
    except yaml.YAMLError as e:
        raise ModelError('not YAML: %s' % str(e).splitlines()[0])
    vm = (cfg or {}).get('Visualization Manager') if isinstance(cfg, dict) else None
    if not isinstance(vm, dict):
        raise ModelError('no "Visualization Manager" section')
    classes = []

    def walk(displays):
        for d in displays or []:
            if isinstance(d, dict):
                if d.get('Enabled', True) is not False:
                    classes.append(str(d.get('Class', '')))
                walk(d.get('Displays'))
    walk(vm.get('Displays'))
    frame = (vm.get('Global Options') or {}).get('Fixed Frame')
    return classes, frame


def rviz_config_arg(argv):
    """The -d/--display-config file of an rviz command line, or None."""
    for i, a in enumerate(argv):
        if a in ('-d', '--display-config') and i + 1 < len(argv):
            return argv[i + 1]
        if a.startswith('--display-config='):
            return a.split('=', 1)[1]
        if a.startswith('-d') and len(a) > 2:
            return a[2:]
    return None


def node_kind(argv):
    """'robot_state_publisher', 'joint_state_publisher', 'rviz' or None from a command line."""
    names = [os.path.basename(a) for a in argv[:2]]
    for n in names:
        if n in ('robot_state_publisher', 'state_publisher'):
            return 'robot_state_publisher'
        if n in ('joint_state_publisher', 'joint_state_publisher_gui'):
            return 'joint_state_publisher'
        if n == 'rviz':
            return 'rviz'
    return None


# --- evaluation ---------------------------------------------------------------------------

def _crit(cid):
    return Criterion(*next(c for c in CRITERIA if c[0] == cid))


def _both(ru, en):
    return reason(ru, en)


def _first(items, more_ru='и ещё', more_en='and'):
    if len(items) <= 1:
        return items[0] if items else '', items[0] if items else ''
    return ('%s (%s %d)' % (items[0], more_ru, len(items) - 1),
            '%s (%s %d more)' % (items[0], more_en, len(items) - 1))


def evaluate(obs):
    """The seven criteria from an observation dict."""
    isu = obs['isu']
    want = spec(isu)
    c = {i: _crit(i) for i in '1234567'}
    model = an = None

    # 1. xacro + check_urdf
    if not obs.get('model_found'):
        c['1'].set(False, _both('нет файла %s в пакете %s' % (MODEL, PACKAGE),
                                'no file %s in package %s' % (MODEL, PACKAGE)))
    elif obs.get('xacro_error'):
        c['1'].set(False, _both('xacro: %s' % obs['xacro_error'], 'xacro: %s' % obs['xacro_error']))
    elif obs.get('check_urdf_error'):
        c['1'].set(False, _both('check_urdf: %s' % obs['check_urdf_error'], 'check_urdf: %s' % obs['check_urdf_error']))
    else:
        try:
            model = parse_urdf(obs['urdf'])
            an = analyse(model)
        except ModelError as e:
            c['1'].set(False, _both('модель не разобрать: %s' % e, 'cannot analyse the model: %s' % e))
            model = None
        if model is not None:
            args = ' '.join(obs.get('xacro_args') or []) or 'без аргументов'
            args_en = ' '.join(obs.get('xacro_args') or []) or 'no args'
            c['1'].set(True, _both('xacro (%s) → %d звеньев, %d шарниров; check_urdf без ошибок' % (args, len(model['links']), len(model['joints'])),
                                   'xacro (%s) -> %d links, %d joints; check_urdf OK' % (args_en, len(model['links']), len(model['joints']))))
    if model is None:
        why = _both('не проверено: модель не раскрылась (критерий 1)', 'not checked: the model did not expand (criterion 1)')
        for i in '23456':
            c[i].set(False, why)
    else:
        # 2. links
        n = len(an['links'])
        total = len(model['links'])
        lst = ', '.join(an['links'])
        if total == want['links']:
            c['2'].set(True, _both('%d звеньев в модели (все <link>, как считает учебник): %s' % (total, ', '.join(sorted(model['links']))),
                                   '%d links in the model (every <link>, as the book counts): %s' % (total, ', '.join(sorted(model['links'])))))
        elif n == want['links']:
            c['2'].set(True, _both('%d звеньев без колёс: %s' % (n, lst), '%d links without wheels: %s' % (n, lst)))
        else:
            c['2'].set(False, _both('в модели %d звеньев (все <link>), без колёс %d (%s), а в варианте %d — годится любой из двух счётов' % (total, n, lst, want['links']),
                                    'the model has %d links (every <link>), %d without wheels (%s); the variant wants %d in either count' % (total, n, lst, want['links'])))
        # 3. manipulator
        desc = ', '.join('%s %s' % (j, model['joints'][j]['type']) for j in an['arm']) or 'none'
        if an['branch']:
            a, b = an['branch']
            c['3'].set(False, _both('подвижные шарниры манипулятора ветвятся (%s и %s): нужна одна цепь' % (a, b),
                                    'the manipulator\'s movable joints branch (%s and %s): one serial chain expected' % (a, b)))
        elif an['arm_codes'] != want['arm']:
            c['3'].set(False, _both('манипулятор %s (%s), а в варианте %s' % (an['arm_codes'] or '—', desc, want['arm']),
                                    'manipulator %s (%s), the variant wants %s' % (an['arm_codes'] or '-', desc, want['arm'])))
        else:
            c['3'].set(True, _both('манипулятор %s: %s' % (an['arm_codes'], desc), 'manipulator %s: %s' % (an['arm_codes'], desc)))
        # 4. wheels
        got = ''.join(sorted(code for _, code in an['wheels']))
        wdesc = ', '.join('%s %s' % (n_, code) for n_, code in an['wheels']) or 'none'
        if got != ''.join(sorted(want['wheels'])):
            c['4'].set(False, _both('колёсные шарниры %s (%s), а в варианте %s' % (got or '—', wdesc, want['wheels']),
                                    'wheel joints %s (%s), the variant wants %s' % (got or '-', wdesc, want['wheels'])))
        else:
            c['4'].set(True, _both('колёсные шарниры %s: %s' % (want['wheels'], wdesc), 'wheel joints %s: %s' % (want['wheels'], wdesc)))
        # 5. body size
        try:
            size = body_size(model, an['body'])
            dims = '%.0f×%.0f×%.0f' % tuple(size)
            off = [abs(a - b) for a, b in zip(size, want['body'])]
            wdims = '%g×%g×%g' % tuple(want['body'])
            if max(off) > SIZE_TOL:
                c['5'].set(False, _both('корпус %s: %s мм, а в варианте %s мм (допуск ±%g мм)' % (an['body'], dims, wdims, SIZE_TOL),
                                        'body %s: %s mm, the variant wants %s mm (tolerance ±%g mm)' % (an['body'], dims.replace('×', 'x'), wdims.replace('×', 'x'), SIZE_TOL)))
            else:
                c['5'].set(True, _both('корпус %s: %s мм' % (an['body'], dims), 'body %s: %s mm' % (an['body'], dims.replace('×', 'x'))))
        except ModelError as e:
            c['5'].set(False, _both('%s' % e, '%s' % e))
        # 6. collision + inertial
        bad = link_problems(model)
        if bad:
            ru, en = _first(bad)
            c['6'].set(False, _both('звено %s' % ru, 'link %s' % en))
        else:
            c['6'].set(True, _both('у всех %d звеньев есть collision и inertial' % len(model['links']),
                                   'all %d links have collision and inertial' % len(model['links'])))

    # 7. the launch file
    c['7'] = evaluate_launch(obs, model, c['7'])
    return [c[i] for i in '1234567']


def evaluate_launch(obs, model, crit):
    la = obs.get('launch') or {}
    if la.get('error'):
        return crit.set(False, _both(la['error'], la['error']))
    desc = la.get('robot_description')
    kinds = la.get('kinds') or {}
    problems = []
    ref = model
    if desc is None:
        problems.append(('параметр /robot_description не задан', 'parameter /robot_description is not set'))
    else:
        try:
            dm = parse_urdf(desc)
            ref = ref or dm
            if model is not None and sorted(dm['links']) != sorted(model['links']):
                problems.append(('в /robot_description другая модель (%d звеньев), не %s' % (len(dm['links']), MODEL),
                                 '/robot_description holds another model (%d links), not %s' % (len(dm['links']), MODEL)))
        except ModelError as e:
            problems.append(('/robot_description: %s' % e, '/robot_description: %s' % e))
    for k in ('robot_state_publisher', 'joint_state_publisher', 'rviz'):
        if not kinds.get(k):
            problems.append(('не запущен узел %s' % k, 'no %s node is running' % k))
    rv = la.get('rviz') or {}
    if kinds.get('rviz'):
        if rv.get('not_up'):
            problems.append(('RViz не открыл окно за %.0f с (не подписался на /tf)' % LAUNCH_LIMIT,
                             'RViz did not open its window within %.0f s (never subscribed to /tf)' % LAUNCH_LIMIT))
        if not rv.get('config'):
            problems.append(('rviz запущен без конфигурации (-d файл.rviz)', 'rviz runs without a config (-d file.rviz)'))
        elif rv.get('config_error'):
            problems.append(('конфигурация RViz %s: %s' % (rv['config'], rv['config_error']),
                             'RViz config %s: %s' % (rv['config'], rv['config_error'])))
        else:
            classes = rv.get('classes') or []
            lack = [short for cls, short in RVIZ_NEEDED if cls not in classes]
            if lack:
                problems.append(('в конфигурации RViz %s нет дисплея %s' % (os.path.basename(rv['config']), ', '.join(lack)),
                                 'RViz config %s has no %s display' % (os.path.basename(rv['config']), ', '.join(lack))))
            frame = rv.get('fixed_frame')
            if ref is not None and frame not in ref['links']:
                problems.append(('Fixed Frame RViz "%s" — не звено модели' % frame,
                                 'RViz Fixed Frame "%s" is not a link of the model' % frame))
    frames = set(la.get('tf_frames') or [])
    if ref is not None:
        missing = sorted(l for l in ref['links'] if l not in frames)
        if missing:
            problems.append(('нет TF звеньев: %s' % ', '.join(missing[:6]), 'no TF for links: %s' % ', '.join(missing[:6])))
    if problems:
        ru = '; '.join(p[0] for p in problems[:3])
        en = '; '.join(p[1] for p in problems[:3])
        return crit.set(False, _both(ru, en))
    nodes = ', '.join('%s=%s' % (k, kinds[k][0]) for k in ('robot_state_publisher', 'joint_state_publisher', 'rviz'))
    return crit.set(True, _both('%s; RViz %s (RobotModel, TF); TF всех %d звеньев за %.0f с' % (nodes, os.path.basename(rv['config']), len(frames), la.get('ready_after', 0)),
                                '%s; RViz %s (RobotModel, TF); TF of all links after %.0f s' % (nodes, os.path.basename(rv['config']), la.get('ready_after', 0))))
