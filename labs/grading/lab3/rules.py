"""Lab 3 rules: `evaluate(obs)` turns an observation (grading.lab3.observer) into the seven
criteria: the model (xacro, check_urdf, links, arm, wheels, body, inertials) and the launch
file (description, nodes, RViz, TF). Pure logic, no rospy; the definitions: grading.lab3.
"""
import os

from grading.common import criteria_by_id, reason
from grading.lab3.criteria import CRITERIA, MODEL, PACKAGE
from grading.lab3.model import analyse, link_problems
from grading.lab3.rviz import RVIZ_NEEDED
from grading.lab3.variants import spec
from grading.urdf import ModelError, body_size, parse_urdf

SIZE_TOL = 5.0          # mm, per dimension of the body box
LAUNCH_LIMIT = 120.0    # s from roslaunch until every piece of criterion 7 is seen (RViz on a loaded machine)
STEP_TIMEOUT = 60.0     # s, xacro and check_urdf each
RVIZ_SETTLE = 3.0       # s RViz must keep running after everything was seen
# s with RViz up, the description set and neither the nodes nor the TF frames changing: what is
# still missing will not come (no need to wait out LAUNCH_LIMIT)
SETTLED = 20.0


def _both(ru, en):
    return reason(ru, en)


def _first(items, more_ru='и ещё', more_en='and'):
    if len(items) <= 1:
        return items[0] if items else '', items[0] if items else ''
    return ('%s (%s %d)' % (items[0], more_ru, len(items) - 1),
            '%s (%s %d more)' % (items[0], more_en, len(items) - 1))


def judge_expansion(c1, obs):
    """Criterion 1: the model expands and passes check_urdf; (model, analysis) or (None, None)."""
    if not obs.get('model_found'):
        c1.set(False, _both('нет файла %s в пакете %s' % (MODEL, PACKAGE),
                            'no file %s in package %s' % (MODEL, PACKAGE)))
    elif obs.get('xacro_error'):
        c1.set(False, _both('xacro: %s' % obs['xacro_error'], 'xacro: %s' % obs['xacro_error']))
    elif obs.get('check_urdf_error'):
        c1.set(False, _both('check_urdf: %s' % obs['check_urdf_error'], 'check_urdf: %s' % obs['check_urdf_error']))
    else:
        try:
            model = parse_urdf(obs['urdf'])
            an = analyse(model)
        except ModelError as e:
            c1.set(False, _both('модель не разобрать: %s' % e, 'cannot analyse the model: %s' % e))
            return None, None
        args = ' '.join(obs.get('xacro_args') or []) or 'без аргументов'
        args_en = ' '.join(obs.get('xacro_args') or []) or 'no args'
        c1.set(True, _both('xacro (%s) → %d звеньев, %d шарниров; check_urdf без ошибок'
                           % (args, len(model['links']), len(model['joints'])),
                           'xacro (%s) -> %d links, %d joints; check_urdf OK'
                           % (args_en, len(model['links']), len(model['joints']))))
        return model, an
    return None, None


def judge_links(c2, model, an, want):
    """Criterion 2: the link count, every <link> or wheels aside."""
    n = len(an['links'])
    total = len(model['links'])
    lst = ', '.join(an['links'])
    if total == want['links']:
        return c2.set(True, _both('%d звеньев в модели (все <link>, как считает учебник): %s'
                                  % (total, ', '.join(sorted(model['links']))),
                                  '%d links in the model (every <link>, as the book counts): %s'
                                  % (total, ', '.join(sorted(model['links'])))))
    if n == want['links']:
        return c2.set(True, _both('%d звеньев без колёс: %s' % (n, lst), '%d links without wheels: %s' % (n, lst)))
    return c2.set(False, _both('в модели %d звеньев (все <link>), без колёс %d (%s), а в варианте %d — '
                               'годится любой из двух счётов' % (total, n, lst, want['links']),
                               'the model has %d links (every <link>), %d without wheels (%s); '
                               'the variant wants %d in either count' % (total, n, lst, want['links'])))


def judge_arm(c3, model, an, want):
    """Criterion 3: the manipulator's joint types, one serial chain."""
    desc = ', '.join('%s %s' % (j, model['joints'][j]['type']) for j in an['arm']) or 'none'
    if an['branch']:
        a, b = an['branch']
        return c3.set(False, _both('подвижные шарниры манипулятора ветвятся (%s и %s): нужна одна цепь' % (a, b),
                                   'the manipulator\'s movable joints branch (%s and %s): one serial chain expected'
                                   % (a, b)))
    if an['arm_codes'] != want['arm']:
        return c3.set(False, _both('манипулятор %s (%s), а в варианте %s' % (an['arm_codes'] or '—', desc, want['arm']),
                                   'manipulator %s (%s), the variant wants %s'
                                   % (an['arm_codes'] or '-', desc, want['arm'])))
    return c3.set(True, _both('манипулятор %s: %s' % (an['arm_codes'], desc),
                              'manipulator %s: %s' % (an['arm_codes'], desc)))


def judge_wheels(c4, an, want):
    """Criterion 4: the wheel joints' number and types."""
    got = ''.join(sorted(code for _, code in an['wheels']))
    wdesc = ', '.join('%s %s' % (n_, code) for n_, code in an['wheels']) or 'none'
    if got != ''.join(sorted(want['wheels'])):
        return c4.set(False, _both('колёсные шарниры %s (%s), а в варианте %s' % (got or '—', wdesc, want['wheels']),
                                   'wheel joints %s (%s), the variant wants %s' % (got or '-', wdesc, want['wheels'])))
    return c4.set(True, _both('колёсные шарниры %s: %s' % (want['wheels'], wdesc),
                              'wheel joints %s: %s' % (want['wheels'], wdesc)))


def judge_body(c5, model, an, want):
    """Criterion 5: the body's box within SIZE_TOL of the variant's."""
    try:
        size = body_size(model, an['body'])
    except ModelError as e:
        return c5.set(False, _both('%s' % e, '%s' % e))
    dims = '%.0f×%.0f×%.0f' % tuple(size)
    off = [abs(a - b) for a, b in zip(size, want['body'])]
    wdims = '%g×%g×%g' % tuple(want['body'])
    if max(off) > SIZE_TOL:
        return c5.set(False, _both('корпус %s: %s мм, а в варианте %s мм (допуск ±%g мм)'
                                   % (an['body'], dims, wdims, SIZE_TOL),
                                   'body %s: %s mm, the variant wants %s mm (tolerance ±%g mm)'
                                   % (an['body'], dims.replace('×', 'x'), wdims.replace('×', 'x'), SIZE_TOL)))
    return c5.set(True, _both('корпус %s: %s мм' % (an['body'], dims),
                              'body %s: %s mm' % (an['body'], dims.replace('×', 'x'))))


def judge_inertials(c6, model):
    """Criterion 6: every link has a collision and a positive-mass inertial."""
    bad = link_problems(model)
    if bad:
        ru, en = _first(bad)
        return c6.set(False, _both('звено %s' % ru, 'link %s' % en))
    return c6.set(True, _both('у всех %d звеньев есть collision и inertial' % len(model['links']),
                              'all %d links have collision and inertial' % len(model['links'])))


def evaluate(obs):
    """The seven criteria from an observation dict."""
    want = spec(obs['isu'])
    c = criteria_by_id(CRITERIA)
    model, an = judge_expansion(c['1'], obs)
    if model is None:
        why = _both('не проверено: модель не раскрылась (критерий 1)',
                    'not checked: the model did not expand (criterion 1)')
        for i in '23456':
            c[i].set(False, why)
    else:
        judge_links(c['2'], model, an, want)
        judge_arm(c['3'], model, an, want)
        judge_wheels(c['4'], an, want)
        judge_body(c['5'], model, an, want)
        judge_inertials(c['6'], model)
    c['7'] = evaluate_launch(obs, model, c['7'])
    return [c[i] for i in '1234567']


def description_problems(desc, model):
    """([(ru, en)], the model to check TF and the fixed frame against) of /robot_description."""
    if desc is None:
        return [('параметр /robot_description не задан', 'parameter /robot_description is not set')], model
    try:
        dm = parse_urdf(desc)
    except ModelError as e:
        return [('/robot_description: %s' % e, '/robot_description: %s' % e)], model
    if model is not None and sorted(dm['links']) != sorted(model['links']):
        return [('в /robot_description другая модель (%d звеньев), не %s' % (len(dm['links']), MODEL),
                 '/robot_description holds another model (%d links), not %s' % (len(dm['links']), MODEL))], model
    return [], model or dm


def rviz_problems(rv, ref):
    """[(ru, en)] of a running RViz: its window, its config's displays and fixed frame."""
    problems = []
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
            problems.append(('в конфигурации RViz %s нет дисплея %s'
                             % (os.path.basename(rv['config']), ', '.join(lack)),
                             'RViz config %s has no %s display' % (os.path.basename(rv['config']), ', '.join(lack))))
        frame = rv.get('fixed_frame')
        if ref is not None and frame not in ref['links']:
            problems.append(('Fixed Frame RViz "%s" — не звено модели' % frame,
                             'RViz Fixed Frame "%s" is not a link of the model' % frame))
    return problems


def evaluate_launch(obs, model, crit):
    """Criterion 7: the launch file's description, nodes, RViz and TF of every link."""
    la = obs.get('launch') or {}
    if la.get('error'):
        return crit.set(False, _both(la['error'], la['error']))
    kinds = la.get('kinds') or {}
    problems, ref = description_problems(la.get('robot_description'), model)
    for k in ('robot_state_publisher', 'joint_state_publisher', 'rviz'):
        if not kinds.get(k):
            problems.append(('не запущен узел %s' % k, 'no %s node is running' % k))
    rv = la.get('rviz') or {}
    if kinds.get('rviz'):
        problems += rviz_problems(rv, ref)
    frames = set(la.get('tf_frames') or [])
    if ref is not None:
        missing = sorted(l for l in ref['links'] if l not in frames)
        if missing:
            problems.append(('нет TF звеньев: %s' % ', '.join(missing[:6]),
                             'no TF for links: %s' % ', '.join(missing[:6])))
    if problems:
        ru = '; '.join(p[0] for p in problems[:3])
        en = '; '.join(p[1] for p in problems[:3])
        return crit.set(False, _both(ru, en))
    nodes = ', '.join('%s=%s' % (k, kinds[k][0]) for k in ('robot_state_publisher', 'joint_state_publisher', 'rviz'))
    return crit.set(True, _both('%s; RViz %s (RobotModel, TF); TF всех %d звеньев за %.0f с'
                                % (nodes, os.path.basename(rv['config']), len(frames), la.get('ready_after', 0)),
                                '%s; RViz %s (RobotModel, TF); TF of all links after %.0f s'
                                % (nodes, os.path.basename(rv['config']), la.get('ready_after', 0))))
