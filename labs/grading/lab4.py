"""Lab 4 rules: a robot of the practical works in a scene of its own, through ros_control.

Pure logic: the scene (SDF world) analysis, the robot description checks and `evaluate(obs)`
that turns an observation (grading.observe.Lab4Observer) into the nine criteria. No rospy.

Time base: every duration of the run is the student's own simulation time (/clock); wall-clock
limits only bound how long the grader waits (generous, for slow machines) and say so.

Definitions (also in labs/lab4/README.md):
  scene object    an <include> of a model:// model other than sun / ground_plane, or an inline
                  <model> with a <mesh> geometry; objects are different when their URIs
                  (include) or mesh URIs (inline) differ;
  light           a <light> or an include of model://sun;  ground: model://ground_plane or a
                  model with a <plane> geometry;  gravity: a <gravity> element, z < 0;
  wheel           a continuous joint whose child link has a cylinder collision;
  by velocity     a running controller that commands the wheel's velocity claims it: by type
                  velocity_controllers/JointVelocityController or JointGroupVelocityController,
                  effort_controllers/JointVelocityController (the book's §12.4: a velocity PID
                  on the EffortJointInterface), diff_drive_controller and the other drive
                  controllers of ros_controllers; a position, trajectory or effort controller
                  does not, whatever its interface; a type unknown here counts when it claims
                  the wheel under VelocityJointInterface;
  collision       a scene object displaced by more than 3 cm (or turned by more than 0.1 rad)
                  during the run, or the robot tipped (roll or pitch above 0.35 rad).
"""
import math
import os
import xml.etree.ElementTree as ET

from grading import package, urdf
from grading.common import Criterion, reason, variant

PACKAGE = 'my_robot_simulation_control'
GRADER_PKG = 'lab4_grader'
LAUNCH = 'lab4.launch'
DEFAULT_TIMEOUT = 480.0
STARTUP_LIMIT = 180.0     # wall s from roslaunch until description, sensors and controllers are seen
RUN_SIM = 40.0            # sim s of motion judged, from the moment every controller runs
RUN_WALL_LIMIT = 240.0    # wall s the grader waits for those RUN_SIM sim seconds
SIZE_TOL = 5.0            # mm
RANGE_TOL = 0.002         # m
MIN_PATH = 1.5            # m travelled within RUN_SIM
MIN_REACH = 1.0           # m from the start point, at the farthest
SPIN_LIMIT = 2 * math.pi  # rad turned per metre travelled
MAX_REVERSALS = 4         # forward/backward changes of direction
PUSH_TOL = 0.03           # m a scene object may move
TURN_TOL = 0.1            # rad a scene object may turn
TILT_LIMIT = 0.35         # rad of robot roll / pitch
DRIVE_PLUGINS = ('diff_drive', 'skid_steer', 'planar_move', 'tricycle')
NOT_OBJECTS = ('sun', 'ground_plane')
VARIANT_ARGS = ('isu', 'variant')
HEADLESS_ARGS = (('gui', 'false'), ('rviz', 'false'), ('headless', 'true'))

CRITERIA = [
    ('1', 'Сцена: свет, земля, гравитация и не менее 3 разных непримитивных объектов',
     'Scene: light, ground, gravity and at least 3 different non-primitive objects'),
    ('2', 'Габариты корпуса по варианту (±5 мм)', 'Body size matches the variant (±5 mm)'),
    ('3', 'Дальность лидара (min/max) по варианту', 'Lidar range (min/max) matches the variant'),
    ('4', 'Разрешение камеры по варианту', 'Camera resolution matches the variant'),
    ('5', 'Контроллеры загружены через controller_manager и запущены, колёса — по скорости',
     'Controllers loaded through controller_manager and running, wheels by velocity'),
    ('6', 'Нет плагина diff-drive / skid-steer в описании робота',
     'No diff-drive / skid-steer plugin in the robot description'),
    ('7', 'Робот проезжает заметное расстояние за отведённое время',
     'The robot covers distance within the time limit'),
    ('8', 'Движение целенаправленное: без вращения на месте и колебаний',
     'Purposeful motion: no spinning in place, no oscillation'),
    ('9', 'Нет столкновений с объектами сцены', 'No collision with the scene'),
]


# controllers of ros_controllers whose command to a wheel is a velocity (drive controllers
# turn a twist into wheel velocities)
DRIVE_CONTROLLERS = ('diff_drive_controller/DiffDriveController',
                     'four_wheel_steering_controller/FourWheelSteeringController',
                     'ackermann_steering_controller/AckermannSteeringController')
NOT_VELOCITY = ('Position', 'Trajectory', 'Gripper')   # what these controllers command


def commands_velocity(ctype, iface):
    """(True/False, what the controller commands) for a controller of type `ctype` that claims
    a joint under hardware interface `iface`."""
    cls = (ctype or '').split('/')[-1]
    if ctype in DRIVE_CONTROLLERS:
        return True, 'velocity'
    for word in NOT_VELOCITY:
        if word in cls:
            return False, word.lower()
    if 'Velocity' in cls:
        return True, 'velocity'
    if 'Effort' in cls:
        return False, 'effort'
    if (iface or '').endswith('VelocityJointInterface'):
        return True, 'velocity'
    return False, 'a type the grader does not know, under %s' % (iface or 'no interface').split('::')[-1]


class SceneError(Exception):
    """The world file cannot be analysed; one line."""


def spec(isu):
    v = variant('lab4', isu)
    return {'lidar': [float(x) for x in v['lidar']], 'camera': [int(x) for x in v['camera']],
            'body': [float(x) for x in v['body']]}


def find_launch(pkg_dir):
    for d, dirs, files in os.walk(pkg_dir):
        dirs[:] = sorted(x for x in dirs if not x.startswith('.') and x not in ('build', 'devel'))
        if LAUNCH in files:
            return os.path.join(d, LAUNCH)
    return None


def launch_args(path, isu):
    """`name:=value` for the variant and headless args the launch file declares."""
    declared = package.launch_args(path)
    out = package.variant_args(declared, isu)
    out += ['%s:=%s' % (n, v) for n, v in HEADLESS_ARGS if n in declared]
    return out


def find_worlds(pkg_dir):
    out = []
    for d, dirs, files in os.walk(pkg_dir):
        dirs[:] = sorted(x for x in dirs if not x.startswith('.') and x not in ('build', 'devel'))
        out += [os.path.join(d, f) for f in sorted(files) if f.endswith(('.world', '.sdf'))
                and 'model.sdf' != f]
    return out


def _local(tag):
    return tag.split('}')[-1] if isinstance(tag, str) else ''


def model_has_mesh(uri, model_dirs):
    """True/False for a model:// URI found in model_dirs, None if not found."""
    name = uri[len('model://'):].strip('/').split('/')[0]
    for d in model_dirs:
        p = os.path.join(d, name, 'model.sdf')
        if os.path.isfile(p):
            with open(p, errors='replace') as f:
                return '<mesh' in f.read()
    return None


def analyse_scene(text):
    """{'light', 'ground', 'gravity', 'objects': [(kind, key, name)], 'names': [...]}"""
    try:
        root = ET.fromstring(text)
    except ET.ParseError as e:
        raise SceneError('not XML: %s' % e)
    world = root if _local(root.tag) == 'world' else next(
        (el for el in root.iter() if _local(el.tag) == 'world'), None)
    if world is None:
        raise SceneError('no <world> element')
    res = {'light': False, 'ground': False, 'gravity': None, 'objects': [], 'names': []}
    for el in world:
        tag = _local(el.tag)
        if tag == 'light':
            res['light'] = True
        elif tag == 'gravity':
            try:
                res['gravity'] = [float(x) for x in (el.text or '').split()]
            except ValueError:
                raise SceneError('<gravity> %r is not 3 numbers' % el.text)
        elif tag == 'include':
            uri = (el.findtext('uri') or '').strip()
            name = (el.findtext('name') or '').strip() or uri.rstrip('/').split('/')[-1]
            res['names'].append(name)
            base = uri[len('model://'):].strip('/').split('/')[0] if uri.startswith('model://') else uri
            if base == 'sun':
                res['light'] = True
            elif base == 'ground_plane':
                res['ground'] = True
            else:
                res['objects'].append(('include', uri, name))
        elif tag == 'model':
            name = el.get('name', '')
            res['names'].append(name)
            geoms = [_local(g.tag) for g in el.iter() if _local(g.tag) in ('mesh', 'plane', 'box', 'sphere', 'cylinder')]
            if 'plane' in geoms:
                res['ground'] = True
            meshes = sorted({(m.findtext('uri') or '').strip() for m in el.iter() if _local(m.tag) == 'mesh'})
            if meshes:
                res['objects'].append(('mesh', ' '.join(meshes), name))
            else:
                res['objects'].append(('primitive', name, name))
    return res


def scene_verdict(scene, model_dirs):
    """(passed, ru, en) of criterion 1."""
    problems = []
    if not scene['light']:
        problems.append(('нет источника света (<light> или model://sun)', 'no light (<light> or model://sun)'))
    if not scene['ground']:
        problems.append(('нет земли (model://ground_plane или <plane>)', 'no ground (model://ground_plane or a <plane>)'))
    g = scene['gravity']
    if not g or len(g) != 3 or not g[2] < 0:
        problems.append(('нет <gravity> с z < 0', 'no <gravity> with z < 0'))
    kinds = {}
    prim = []
    for kind, key, name in scene['objects']:
        if kind == 'primitive':
            prim.append(name)
            continue
        if kind == 'include' and key.startswith('model://') and model_has_mesh(key, model_dirs) is False:
            prim.append(name)
            continue
        kinds.setdefault(key, name)
    objs = ', '.join(sorted(kinds.values()))
    if len(kinds) < 3:
        extra_ru = ' (примитивы не считаются: %s)' % ', '.join(prim) if prim else ''
        extra_en = ' (primitives do not count: %s)' % ', '.join(prim) if prim else ''
        problems.append(('разных непримитивных объектов %d (%s), нужно не менее 3%s' % (len(kinds), objs or '—', extra_ru),
                         '%d different non-primitive objects (%s), at least 3 needed%s' % (len(kinds), objs or 'none', extra_en)))
    if problems:
        return False, '; '.join(p[0] for p in problems), '; '.join(p[1] for p in problems)
    return True, 'свет, земля, гравитация %s; объекты: %s' % (' '.join('%g' % x for x in g), objs), \
        'light, ground, gravity %s; objects: %s' % (' '.join('%g' % x for x in g), objs)


def drive_plugins(urdf_text):
    """Filenames of drive plugins in a robot description."""
    try:
        root = ET.fromstring(urdf_text)
    except ET.ParseError:
        return []
    return [p.get('filename', '') for p in root.iter('plugin')
            if any(k in (p.get('filename', '') + p.get('name', '')).lower() for k in DRIVE_PLUGINS)]


def wheel_joints(model):
    return sorted(n for n, j in model['joints'].items()
                  if j['type'] == 'continuous' and 'cylinder' in [c[0] for c in model['links'][j['child']]['collisions']])


def _yaw(q):
    x, y, z, w = q
    return math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))


def _tilt(q):
    x, y, z, w = q
    roll = math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
    pitch = math.asin(max(-1.0, min(1.0, 2 * (w * y - z * x))))
    return max(abs(roll), abs(pitch))


def motion(samples):
    """Metrics of a robot track [(t, x, y, z, qx, qy, qz, qw)] (t: sim time)."""
    if len(samples) < 2:
        return None
    x0, y0 = samples[0][1], samples[0][2]
    path = reach = turned = 0.0
    tilt = 0.0
    prev = samples[0]
    for s in samples[1:]:
        path += math.hypot(s[1] - prev[1], s[2] - prev[2])
        d = _yaw(s[4:8]) - _yaw(prev[4:8])
        turned += abs(math.atan2(math.sin(d), math.cos(d)))
        reach = max(reach, math.hypot(s[1] - x0, s[2] - y0))
        tilt = max(tilt, _tilt(s[4:8]))
        prev = s
    # forward / backward reversals: velocity along the heading over 0.5 s windows
    reversals, sign, last = 0, 0, samples[0]
    for s in samples[1:]:
        if s[0] - last[0] < 0.5:
            continue
        h = _yaw(last[4:8])
        v = ((s[1] - last[1]) * math.cos(h) + (s[2] - last[2]) * math.sin(h)) / (s[0] - last[0])
        if abs(v) > 0.03:
            sg = 1 if v > 0 else -1
            if sign and sg != sign:
                reversals += 1
            sign = sg
        last = s
    return {'duration': samples[-1][0] - samples[0][0], 'path': path, 'reach': reach,
            'turned': turned, 'reversals': reversals, 'tilt': tilt}


def pushed(objects):
    """[(name, moved m, turned rad)] of scene objects that moved beyond the tolerances;
    objects = {name: (first pose, last pose)} with poses (x, y, z, qx, qy, qz, qw)."""
    out = []
    for name, (a, b) in sorted(objects.items()):
        moved = math.sqrt(sum((p - q) ** 2 for p, q in zip(a[:3], b[:3])))
        d = _yaw(b[3:7]) - _yaw(a[3:7])
        turned = abs(math.atan2(math.sin(d), math.cos(d)))
        if moved > PUSH_TOL or turned > TURN_TOL or _tilt(b[3:7]) > _tilt(a[3:7]) + TURN_TOL:
            out.append((name, moved, turned))
    return out


def _crit(cid):
    return Criterion(*next(c for c in CRITERIA if c[0] == cid))


def evaluate(obs):
    want = spec(obs['isu'])
    c = {i: _crit(i) for i in '123456789'}
    la = obs.get('launch') or {}
    err = la.get('error')
    sfx_ru = ' (%s)' % err if err else ''
    sfx_en = ' (%s)' % err if err else ''

    # 1. scene
    sc = obs.get('scene') or {}
    if sc.get('error'):
        c['1'].set(False, reason(sc['error_ru'] if sc.get('error_ru') else sc['error'], sc['error']))
    else:
        try:
            ok, ru, en = scene_verdict(analyse_scene(sc['text']), obs.get('model_dirs') or [])
            f = os.path.basename(sc['path'])
            c['1'].set(ok, reason('%s: %s' % (f, ru), '%s: %s' % (f, en)))
        except SceneError as e:
            c['1'].set(False, reason('%s: %s' % (os.path.basename(sc['path']), e), '%s: %s' % (os.path.basename(sc['path']), e)))

    # 2. body, 6. plugins (from /robot_description)
    desc = la.get('robot_description')
    model = None
    if desc is None:
        why = reason('параметр /robot_description не появился за %.0f с (настенное время)%s' % (STARTUP_LIMIT, sfx_ru),
                     'parameter /robot_description did not appear within %.0f s (wall clock)%s' % (STARTUP_LIMIT, sfx_en))
        c['2'].set(False, why)
        c['6'].set(False, why)
    else:
        try:
            model = urdf.parse_urdf(desc)
            an_body = urdf.body_link(model)
            size = urdf.body_size(model, an_body)
            off = max(abs(a - b) for a, b in zip(size, want['body']))
            dims = '%.0fx%.0fx%.0f' % tuple(size)
            wdims = '%gx%gx%g' % tuple(want['body'])
            if off > SIZE_TOL:
                c['2'].set(False, reason('корпус %s: %s мм, а в варианте %s мм (допуск ±%g мм)' % (an_body, dims, wdims, SIZE_TOL),
                                         'body %s: %s mm, the variant wants %s mm (tolerance ±%g mm)' % (an_body, dims, wdims, SIZE_TOL)))
            else:
                c['2'].set(True, reason('корпус %s: %s мм' % (an_body, dims), 'body %s: %s mm' % (an_body, dims)))
        except urdf.ModelError as e:
            c['2'].set(False, reason('/robot_description: %s' % e, '/robot_description: %s' % e))
        plugins = drive_plugins(desc)
        if plugins:
            c['6'].set(False, reason('в описании робота плагин движения %s: нужен ros_control' % ', '.join(plugins),
                                     'the robot description has the drive plugin %s: use ros_control instead' % ', '.join(plugins)))
        else:
            c['6'].set(True, reason('плагинов diff-drive / skid-steer нет', 'no diff-drive / skid-steer plugin'))

    # 3. lidar
    scans = la.get('scans') or {}
    lo, hi = want['lidar']
    if not scans:
        c['3'].set(False, reason('нет ни одного топика sensor_msgs/LaserScan с сообщениями за %.0f с (настенное время)%s' % (STARTUP_LIMIT, sfx_ru),
                                 'no sensor_msgs/LaserScan topic delivered a message within %.0f s (wall clock)%s' % (STARTUP_LIMIT, sfx_en)))
    else:
        good = [t for t, (a, b) in sorted(scans.items()) if abs(a - lo) <= RANGE_TOL and abs(b - hi) <= RANGE_TOL]
        desc_s = ', '.join('%s %g-%g m' % (t, a, b) for t, (a, b) in sorted(scans.items()))
        if good:
            c['3'].set(True, reason('%s: %g–%g м' % (good[0], lo, hi), '%s: %g-%g m' % (good[0], lo, hi)))
        else:
            c['3'].set(False, reason('лидар %s, а в варианте %g–%g м' % (desc_s, lo, hi),
                                     'lidar %s, the variant wants %g-%g m' % (desc_s, lo, hi)))

    # 4. camera
    imgs = la.get('images') or {}
    w, h = want['camera']
    if not imgs:
        c['4'].set(False, reason('нет ни одного топика sensor_msgs/Image с кадрами за %.0f с (настенное время)%s' % (STARTUP_LIMIT, sfx_ru),
                                 'no sensor_msgs/Image topic delivered a frame within %.0f s (wall clock)%s' % (STARTUP_LIMIT, sfx_en)))
    else:
        good = [t for t, (a, b) in sorted(imgs.items()) if (a, b) == (w, h)]
        desc_i = ', '.join('%s %dx%d' % (t, a, b) for t, (a, b) in sorted(imgs.items()))
        if good:
            c['4'].set(True, reason('%s: %dx%d' % (good[0], w, h), '%s: %dx%d' % (good[0], w, h)))
        else:
            c['4'].set(False, reason('камера %s, а в варианте %dx%d' % (desc_i, w, h),
                                     'camera %s, the variant wants %dx%d' % (desc_i, w, h)))

    # 5. controllers
    ctrls = la.get('controllers')
    if not ctrls:
        c['5'].set(False, reason('controller_manager не найден или не загрузил ни одного контроллера за %.0f с (настенное время)%s' % (STARTUP_LIMIT, sfx_ru),
                                 'no controller_manager, or it loaded no controller, within %.0f s (wall clock)%s' % (STARTUP_LIMIT, sfx_en)))
    else:
        not_running = ['%s (%s)' % (n, d['state']) for n, d in sorted(ctrls.items()) if d['state'] != 'running']
        by_vel, other = set(), {}
        for n, d in sorted(ctrls.items()):
            if d['state'] == 'running':
                for iface, res in d['claimed']:
                    ok, what = commands_velocity(d.get('type'), iface)
                    for r in res:
                        if ok:
                            by_vel.add(r)
                        else:
                            other.setdefault(r, '%s (%s, %s)' % (n, d.get('type'), what))
        wheels = wheel_joints(model) if model else []
        missing = [j for j in wheels if j not in by_vel]
        miss_txt = ', '.join('%s by %s' % (j, other[j]) if j in other else '%s by no running controller' % j
                             for j in missing)
        names = ', '.join('%s %s' % (n, d['type']) for n, d in sorted(ctrls.items()))
        if not_running:
            c['5'].set(False, reason('контроллеры не запущены: %s' % ', '.join(not_running),
                                     'controllers not running: %s' % ', '.join(not_running)))
        elif not wheels:
            c['5'].set(False, reason('в описании робота нет колёс (continuous-шарниров с цилиндром)',
                                     'the robot description has no wheels (continuous joints with a cylinder collision)'))
        elif missing:
            vel_ru = miss_txt.replace(' by no running controller', ': нет запущенного контроллера').replace(' by ', ': ')
            c['5'].set(False, reason('колёса управляются не по скорости: %s; нужен контроллер скорости (velocity_controllers, effort_controllers/JointVelocityController, diff_drive_controller)' % vel_ru,
                                     'wheels not controlled by velocity: %s; a velocity controller is needed (velocity_controllers, effort_controllers/JointVelocityController, diff_drive_controller)' % miss_txt))
        else:
            c['5'].set(True, reason('%s; колёса %s по скорости' % (names, ', '.join(wheels)),
                                    '%s; wheels %s by velocity' % (names, ', '.join(wheels))))

    # 7-9. motion (sim time)
    mv = la.get('motion') or {}
    m = motion(mv.get('track') or [])
    if mv.get('error') or m is None:
        e = mv.get('error') or 'the robot was not seen in /gazebo/model_states'
        e_ru = mv.get('error_ru') or 'робот не найден в /gazebo/model_states'
        for i in '789':
            c[i].set(False, reason('не проверено: %s%s' % (e_ru, sfx_ru), 'not checked: %s%s' % (e, sfx_en)))
        return [c[i] for i in '123456789']
    robot = mv.get('robot', '?')
    dur = m['duration']
    short = dur < RUN_SIM - 0.5
    why_short_ru = '; за %.0f с настенного времени прошло лишь %.1f с времени симуляции' % (RUN_WALL_LIMIT, dur) if short else ''
    why_short_en = '; only %.1f s of sim time passed within %.0f s of wall clock' % (dur, RUN_WALL_LIMIT) if short else ''
    if m['path'] < MIN_PATH or m['reach'] < MIN_REACH:
        c['7'].set(False, reason('%s за %.1f с времени симуляции проехал %.2f м и удалился от старта на %.2f м; нужно не менее %.1f м и %.1f м%s'
                                 % (robot, dur, m['path'], m['reach'], MIN_PATH, MIN_REACH, why_short_ru),
                                 '%s travelled %.2f m and got %.2f m from the start in %.1f s of sim time; at least %.1f m and %.1f m needed%s'
                                 % (robot, m['path'], m['reach'], dur, MIN_PATH, MIN_REACH, why_short_en)))
    else:
        c['7'].set(True, reason('%s: %.2f м за %.1f с времени симуляции, до %.2f м от старта' % (robot, m['path'], dur, m['reach']),
                                '%s: %.2f m in %.1f s of sim time, up to %.2f m from the start' % (robot, m['path'], dur, m['reach'])))
    rate = m['turned'] / max(m['path'], 0.05)
    if m['path'] < MIN_PATH / 3:
        c['8'].set(False, reason('не проверено: робот почти не двигался (%.2f м, повернулся на %.1f рад)' % (m['path'], m['turned']),
                                 'not judged: the robot hardly moved (%.2f m, turned %.1f rad)' % (m['path'], m['turned'])))
    elif rate > SPIN_LIMIT:
        c['8'].set(False, reason('вращение на месте: %.1f рад поворота на %.2f м пути (не более %.1f рад/м)' % (m['turned'], m['path'], SPIN_LIMIT),
                                 'spinning in place: turned %.1f rad over %.2f m (at most %.1f rad/m)' % (m['turned'], m['path'], SPIN_LIMIT)))
    elif m['reversals'] > MAX_REVERSALS:
        c['8'].set(False, reason('колебания: %d смен направления вперёд/назад за %.1f с (не более %d)' % (m['reversals'], dur, MAX_REVERSALS),
                                 'oscillation: %d forward/backward reversals in %.1f s (at most %d)' % (m['reversals'], dur, MAX_REVERSALS)))
    else:
        c['8'].set(True, reason('%.1f рад/м поворота, %d смен направления' % (rate, m['reversals']),
                                '%.1f rad/m turned, %d reversals' % (rate, m['reversals'])))
    hits = pushed(mv.get('objects') or {})
    if hits:
        d = ', '.join('%s (сдвинут на %.2f м)' % (n, a) for n, a, _ in hits[:3])
        d_en = ', '.join('%s (moved %.2f m)' % (n, a) for n, a, _ in hits[:3])
        c['9'].set(False, reason('столкновение: %s' % d, 'collision: %s' % d_en))
    elif m['tilt'] > TILT_LIMIT:
        c['9'].set(False, reason('робот опрокинулся или наехал на объект (наклон %.2f рад)' % m['tilt'],
                                 'the robot tipped or climbed onto something (tilt %.2f rad)' % m['tilt']))
    else:
        c['9'].set(True, reason('объекты сцены (%d) не сдвинуты' % len(mv.get('objects') or {}),
                                'scene objects (%d) not displaced' % len(mv.get('objects') or {})))
    return [c[i] for i in '123456789']
