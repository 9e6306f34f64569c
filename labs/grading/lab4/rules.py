"""Lab 4 rules: `evaluate(obs)` turns an observation (grading.lab4.observer) into the nine
criteria: scene, body, lidar, camera, controllers, no drive plugin, distance, purposeful motion,
no collision. Pure logic, no rospy; the definitions and the time base: grading.lab4.
"""
import math
import os

from grading.common import criteria_by_id, reason
from grading.lab4.criteria import CRITERIA
from grading.lab4.motion import motion, pushed
from grading.lab4.robot import commands_velocity, drive_plugins, wheel_joints
from grading.lab4.scene import SceneError, analyse_scene, scene_verdict
from grading.lab4.variants import spec
from grading import package
from grading.urdf import ModelError, body_link, body_size, parse_urdf

STARTUP_LIMIT = 180.0     # wall s from roslaunch until description, sensors and controllers are seen
RUN_SIM = 40.0            # sim s of motion judged, from the moment every controller runs
RUN_WALL_LIMIT = 240.0    # wall s the grader waits for those RUN_SIM sim seconds
SIZE_TOL = 5.0            # mm
RANGE_TOL = 0.002         # m
MIN_PATH = 1.5            # m travelled within RUN_SIM
MIN_REACH = 1.0           # m from the start point, at the farthest
SPIN_LIMIT = 2 * math.pi  # rad turned per metre travelled
MAX_REVERSALS = 4         # forward/backward changes of direction
TILT_LIMIT = 0.35         # rad of robot roll / pitch
HEADLESS_ARGS = (('gui', 'false'), ('rviz', 'false'), ('headless', 'true'))


def roslaunch_args(path, isu):
    """`name:=value` for the variant and headless args the launch file declares."""
    declared = package.launch_args(path)
    out = package.variant_args(declared, isu)
    out += ['%s:=%s' % (n, v) for n, v in HEADLESS_ARGS if n in declared]
    return out


def judge_scene(c, obs):
    """Criterion 1: the scene's light, ground, gravity and objects."""
    sc = obs.get('scene') or {}
    if sc.get('error'):
        c['1'].set(False, reason(sc['error_ru'] if sc.get('error_ru') else sc['error'], sc['error']))
    else:
        try:
            ok, ru, en = scene_verdict(analyse_scene(sc['text']), obs.get('model_dirs') or [])
            f = os.path.basename(sc['path'])
            c['1'].set(ok, reason('%s: %s' % (f, ru), '%s: %s' % (f, en)))
        except SceneError as e:
            f = os.path.basename(sc['path'])
            c['1'].set(False, reason('%s: %s' % (f, e), '%s: %s' % (f, e)))


def judge_description(c, la, want, sfx_ru, sfx_en):
    """Criteria 2 (body size) and 6 (no drive plugin) from /robot_description; the parsed
    model, or None."""
    desc = la.get('robot_description')
    model = None
    if desc is None:
        why = reason('параметр /robot_description не появился за %.0f с (настенное время)%s' % (STARTUP_LIMIT, sfx_ru),
                     'parameter /robot_description did not appear within %.0f s (wall clock)%s'
                     % (STARTUP_LIMIT, sfx_en))
        c['2'].set(False, why)
        c['6'].set(False, why)
    else:
        try:
            model = parse_urdf(desc)
            an_body = body_link(model)
            size = body_size(model, an_body)
            off = max(abs(a - b) for a, b in zip(size, want['body']))
            dims = '%.0fx%.0fx%.0f' % tuple(size)
            wdims = '%gx%gx%g' % tuple(want['body'])
            if off > SIZE_TOL:
                c['2'].set(False, reason('корпус %s: %s мм, а в варианте %s мм (допуск ±%g мм)'
                                         % (an_body, dims, wdims, SIZE_TOL),
                                         'body %s: %s mm, the variant wants %s mm (tolerance ±%g mm)'
                                         % (an_body, dims, wdims, SIZE_TOL)))
            else:
                c['2'].set(True, reason('корпус %s: %s мм' % (an_body, dims), 'body %s: %s mm' % (an_body, dims)))
        except ModelError as e:
            c['2'].set(False, reason('/robot_description: %s' % e, '/robot_description: %s' % e))
        plugins = drive_plugins(desc)
        if plugins:
            c['6'].set(False, reason('в описании робота плагин движения %s: нужен ros_control' % ', '.join(plugins),
                                     'the robot description has the drive plugin %s: use ros_control instead'
                                     % ', '.join(plugins)))
        else:
            c['6'].set(True, reason('плагинов diff-drive / skid-steer нет', 'no diff-drive / skid-steer plugin'))
    return model


def judge_lidar(c, la, want, sfx_ru, sfx_en):
    """Criterion 3: a LaserScan topic with the variant's range."""
    scans = la.get('scans') or {}
    lo, hi = want['lidar']
    if not scans:
        c['3'].set(False, reason('нет ни одного топика sensor_msgs/LaserScan с сообщениями за %.0f с '
                                 '(настенное время)%s' % (STARTUP_LIMIT, sfx_ru),
                                 'no sensor_msgs/LaserScan topic delivered a message within %.0f s (wall clock)%s'
                                 % (STARTUP_LIMIT, sfx_en)))
    else:
        good = [t for t, (a, b) in sorted(scans.items()) if abs(a - lo) <= RANGE_TOL and abs(b - hi) <= RANGE_TOL]
        desc_s = ', '.join('%s %g-%g m' % (t, a, b) for t, (a, b) in sorted(scans.items()))
        if good:
            c['3'].set(True, reason('%s: %g–%g м' % (good[0], lo, hi), '%s: %g-%g m' % (good[0], lo, hi)))
        else:
            c['3'].set(False, reason('лидар %s, а в варианте %g–%g м' % (desc_s, lo, hi),
                                     'lidar %s, the variant wants %g-%g m' % (desc_s, lo, hi)))


def judge_camera(c, la, want, sfx_ru, sfx_en):
    """Criterion 4: an Image topic with the variant's resolution."""
    imgs = la.get('images') or {}
    w, h = want['camera']
    if not imgs:
        c['4'].set(False, reason('нет ни одного топика sensor_msgs/Image с кадрами за %.0f с (настенное время)%s'
                                 % (STARTUP_LIMIT, sfx_ru),
                                 'no sensor_msgs/Image topic delivered a frame within %.0f s (wall clock)%s'
                                 % (STARTUP_LIMIT, sfx_en)))
    else:
        good = [t for t, (a, b) in sorted(imgs.items()) if (a, b) == (w, h)]
        desc_i = ', '.join('%s %dx%d' % (t, a, b) for t, (a, b) in sorted(imgs.items()))
        if good:
            c['4'].set(True, reason('%s: %dx%d' % (good[0], w, h), '%s: %dx%d' % (good[0], w, h)))
        else:
            c['4'].set(False, reason('камера %s, а в варианте %dx%d' % (desc_i, w, h),
                                     'camera %s, the variant wants %dx%d' % (desc_i, w, h)))


def judge_controllers(c, la, model, sfx_ru, sfx_en):
    """Criterion 5: every controller running, every wheel by velocity."""
    ctrls = la.get('controllers')
    if not ctrls:
        c['5'].set(False, reason('controller_manager не найден или не загрузил ни одного контроллера за %.0f с '
                                 '(настенное время)%s' % (STARTUP_LIMIT, sfx_ru),
                                 'no controller_manager, or it loaded no controller, within %.0f s (wall clock)%s'
                                 % (STARTUP_LIMIT, sfx_en)))
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
                                     'the robot description has no wheels '
                                     '(continuous joints with a cylinder collision)'))
        elif missing:
            vel_ru = (miss_txt.replace(' by no running controller', ': нет запущенного контроллера')
                      .replace(' by ', ': '))
            c['5'].set(False, reason('колёса управляются не по скорости: %s; нужен контроллер скорости '
                                     '(velocity_controllers, effort_controllers/JointVelocityController, '
                                     'diff_drive_controller)' % vel_ru,
                                     'wheels not controlled by velocity: %s; a velocity controller is needed '
                                     '(velocity_controllers, effort_controllers/JointVelocityController, '
                                     'diff_drive_controller)' % miss_txt))
        else:
            c['5'].set(True, reason('%s; колёса %s по скорости' % (names, ', '.join(wheels)),
                                    '%s; wheels %s by velocity' % (names, ', '.join(wheels))))


def judge_motion(c, la, sfx_ru, sfx_en):
    """Criteria 7 (distance), 8 (purposeful) and 9 (no collision), on sim time."""
    mv = la.get('motion') or {}
    m = motion(mv.get('track') or [])
    if mv.get('error') or m is None:
        e = mv.get('error') or 'the robot was not seen in /gazebo/model_states'
        e_ru = mv.get('error_ru') or 'робот не найден в /gazebo/model_states'
        for i in '789':
            c[i].set(False, reason('не проверено: %s%s' % (e_ru, sfx_ru), 'not checked: %s%s' % (e, sfx_en)))
        return
    robot = mv.get('robot', '?')
    dur = m['duration']
    short = dur < RUN_SIM - 0.5
    why_short_ru = ('; за %.0f с настенного времени прошло лишь %.1f с времени симуляции' % (RUN_WALL_LIMIT, dur)
                    if short else '')
    why_short_en = ('; only %.1f s of sim time passed within %.0f s of wall clock' % (dur, RUN_WALL_LIMIT)
                    if short else '')
    if m['path'] < MIN_PATH or m['reach'] < MIN_REACH:
        c['7'].set(False, reason('%s за %.1f с времени симуляции проехал %.2f м и удалился от старта на %.2f м; '
                                 'нужно не менее %.1f м и %.1f м%s'
                                 % (robot, dur, m['path'], m['reach'], MIN_PATH, MIN_REACH, why_short_ru),
                                 '%s travelled %.2f m and got %.2f m from the start in %.1f s of sim time; '
                                 'at least %.1f m and %.1f m needed%s'
                                 % (robot, m['path'], m['reach'], dur, MIN_PATH, MIN_REACH, why_short_en)))
    else:
        c['7'].set(True, reason('%s: %.2f м за %.1f с времени симуляции, до %.2f м от старта'
                                % (robot, m['path'], dur, m['reach']),
                                '%s: %.2f m in %.1f s of sim time, up to %.2f m from the start'
                                % (robot, m['path'], dur, m['reach'])))
    rate = m['turned'] / max(m['path'], 0.05)
    if m['path'] < MIN_PATH / 3:
        c['8'].set(False, reason('не проверено: робот почти не двигался (%.2f м, повернулся на %.1f рад)'
                                 % (m['path'], m['turned']),
                                 'not judged: the robot hardly moved (%.2f m, turned %.1f rad)'
                                 % (m['path'], m['turned'])))
    elif rate > SPIN_LIMIT:
        c['8'].set(False, reason('вращение на месте: %.1f рад поворота на %.2f м пути (не более %.1f рад/м)'
                                 % (m['turned'], m['path'], SPIN_LIMIT),
                                 'spinning in place: turned %.1f rad over %.2f m (at most %.1f rad/m)'
                                 % (m['turned'], m['path'], SPIN_LIMIT)))
    elif m['reversals'] > MAX_REVERSALS:
        c['8'].set(False, reason('колебания: %d смен направления вперёд/назад за %.1f с (не более %d)'
                                 % (m['reversals'], dur, MAX_REVERSALS),
                                 'oscillation: %d forward/backward reversals in %.1f s (at most %d)'
                                 % (m['reversals'], dur, MAX_REVERSALS)))
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


def evaluate(obs):
    want = spec(obs['isu'])
    c = criteria_by_id(CRITERIA)
    la = obs.get('launch') or {}
    err = la.get('error')
    sfx_ru = ' (%s)' % err if err else ''
    sfx_en = ' (%s)' % err if err else ''
    judge_scene(c, obs)
    model = judge_description(c, la, want, sfx_ru, sfx_en)
    judge_lidar(c, la, want, sfx_ru, sfx_en)
    judge_camera(c, la, want, sfx_ru, sfx_en)
    judge_controllers(c, la, model, sfx_ru, sfx_en)
    judge_motion(c, la, sfx_ru, sfx_en)
    return [c[i] for i in '123456789']
