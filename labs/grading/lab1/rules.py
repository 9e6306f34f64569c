"""Lab 1 rules: three nodes, the variant's computing node, operation and result topic.

Pure logic: `evaluate(obs)` turns an observation (gathered by grading.lab1.observer on a
running graph) into the four criteria. No rospy here.
"""
import math
import os

from grading.common import criteria_by_id, reason
from grading.lab1.criteria import CRITERIA
from grading.lab1.variants import NODES, operations, roles

STARTUP_LIMIT = 60.0   # s from start until every node is up and the first result arrives (generous: a
# loaded machine starts three rospy nodes slowly; a working solution needs ~3 s)
OBSERVE = 8.0          # s of observation after the first result
SILENT = 20.0          # s with the same nodes up and none advertising the result topic: a solution
# advertises it as it starts, so the rest of STARTUP_LIMIT is not waited out
AFTER_EXIT = 10.0      # s without a result after a node exited: it will not come (nothing restarts
# the node), so the rest of STARTUP_LIMIT is not waited out
MIN_RESULTS = 3        # result messages needed in the observation ("repeatedly")
MAX_GAP = 5.0          # s, largest allowed pause between two results
WINDOW = 10.0          # s before a result: operands the computing node may still have held
LAG = 3.0              # s after a result: operands the checker may see only after the result
ABS_TOL = 1e-3         # |result - expected| <= ABS_TOL + REL_TOL * |expected|
REL_TOL = 1e-4


def apply_op(op, a, b):
    if op == '+':
        return a + b
    if op == '-':
        return a - b
    if op == '*':
        return a * b
    if op == '/':
        return a / b if b != 0 else math.nan
    raise ValueError('unknown operation %r' % op)


def close(value, expected):
    return math.isfinite(expected) and abs(value - expected) <= ABS_TOL + REL_TOL * abs(expected)


def result_topics(isu, comp):
    """Accepted names of the result topic: the relative name resolved in the root
    namespace (/result_ISU) or the computing node's private name (/nodeN/result_ISU)."""
    return ['/result_%s' % isu, '/%s/result_%s' % (comp, isu)]


def node_scripts(pkg_dir):
    """Node scripts of a package: *.py outside src/ and test/ (setup.py aside) that are
    executable or call init_node."""
    found = {}
    for d, dirs, files in os.walk(pkg_dir):
        rel = os.path.relpath(d, pkg_dir)
        top = rel.split(os.sep)[0]
        if rel != '.' and (top in ('src', 'test', 'tests', 'build', 'devel') or top.startswith('.')):
            dirs[:] = []
            continue
        for f in files:
            if f.endswith('.py') and f != 'setup.py':
                p = os.path.join(d, f)
                try:
                    with open(p, errors='replace') as fh:
                        text = fh.read()
                except OSError:
                    continue
                if 'init_node' in text or os.access(p, os.X_OK):
                    found.setdefault(f, p)
    return found


def candidates(series, t, window=WINDOW, lag=LAG):
    """Values of an operand series (checker receive time, value) that may have produced a result
    the checker received at t, by causality rather than by the checker's clock.

    The computing node used the latest operands *it* had received when it published. The checker
    receives operands and the result on separate connections, each delayed by its own amount
    (seconds on a loaded machine), so that operand may reach the checker after the result
    (`lag`), and the computing node may still hold an operand the checker replaced earlier
    (`window`). The latest value before t is always a candidate, however old: a slow sender is
    not a wrong answer. Empty when the checker had no value before t: then it may have missed
    the operand that was used (it subscribes only once it sees the topic), and the result is
    not judged at all."""
    before = [v for (ts, v) in series if ts <= t]
    if not before:
        return []
    near = [v for (ts, v) in series if t - window <= ts <= t + lag]
    if before[-1] not in near:
        near.append(before[-1])
    return near


def match_results(results, first, second, op, int_result=False):
    """(verified, wrong, example of a wrong one) over result messages with known operands."""
    verified, wrong, example = 0, 0, None
    for t, r in results:
        a_s, b_s = candidates(first, t), candidates(second, t)
        if not a_s or not b_s:
            continue
        ok = False
        for a in a_s:
            for b in b_s:
                e = apply_op(op, a, b)
                if close(r, e) or (int_result and op == '/' and math.isfinite(e) and close(r, float(int(e)))):
                    ok = True
        verified += 1
        if not ok:
            wrong += 1
            if example is None:   # shown with the operands the checker had last before the result
                a = [v for ts, v in first if ts <= t][-1]
                b = [v for ts, v in second if ts <= t][-1]
                example = (r, a, b, apply_op(op, a, b))
    return verified, wrong, example


def fmt(x):
    return '%g' % x


def judge_nodes(c1, obs):
    """Criterion 1: exactly node1..3, each script executable, none crashed."""
    scripts = sorted(obs.get('scripts', []))
    nodes = sorted(obs.get('nodes', []))
    procs = obs.get('procs', {})
    crashed = ['%s.py exited with code %s: %s' % (n, p['rc'], p.get('last', ''))
               for n, p in sorted(procs.items()) if p.get('rc') not in (None,)]
    missing = [n + '.py' for n in NODES if n + '.py' not in scripts]
    extra = [s for s in scripts if s not in [n + '.py' for n in NODES]]
    not_exec = obs.get('not_executable', [])
    want_nodes = ['/' + n for n in NODES]
    if missing:
        c1.set(False, reason('нет скриптов узлов: %s' % ', '.join(missing),
                             'missing node scripts: %s' % ', '.join(missing)))
    elif extra:
        c1.set(False, reason('лишние узлы в пакете (нужно ровно три): %s' % ', '.join(extra),
                             'extra node scripts in the package (exactly three wanted): %s' % ', '.join(extra)))
    elif not_exec:
        c1.set(False, reason('скрипт не исполняемый (chmod +x): %s' % ', '.join(not_exec),
                             'script is not executable (chmod +x): %s' % ', '.join(not_exec)))
    elif crashed:
        c1.set(False, reason('узел упал: %s' % crashed[0], 'a node crashed: %s' % crashed[0]))
    elif nodes != want_nodes:
        c1.set(False, reason('в графе узлы %s, а нужны %s' % (', '.join(nodes) or 'нет', ', '.join(want_nodes)),
                             'nodes in the graph: %s; wanted: %s'
                             % (', '.join(nodes) or 'none', ', '.join(want_nodes))))
    else:
        c1.set(True, reason('работают узлы %s' % ', '.join(nodes), 'running nodes: %s' % ', '.join(nodes)))


def judge_topics(c2, obs, isu):
    """Criterion 2; returns (the result topic or None, {sender: topics the computing node
    takes from it})."""
    comp, (s1, s2), _ = roles(isu)
    pubs, subs = obs.get('pubs', {}), obs.get('subs', {})
    cn = '/' + comp
    accepted = result_topics(isu, comp)
    res_topic = next((t for t in accepted if t in pubs.get(cn, [])), None)
    in_topics = {s: sorted(set(subs.get(cn, [])) & set(pubs.get('/' + s, []))) for s in (s1, s2)}
    if res_topic is None:
        others = sorted(t for n, ts in pubs.items() for t in ts if t.endswith('result_%s' % isu))
        where = ('; result_%s publishes %s' % (isu, ', '.join(n for n, ts in sorted(pubs.items())
                                                              if any(t.endswith('result_' + isu) for t in ts)))
                 if others else '')
        c2.set(False, reason('узел %s (вариант %s) не публикует %s%s' % (comp, isu[-1], ' или '.join(accepted), where),
                             'node %s (variant %s) does not publish %s%s'
                             % (comp, isu[-1], ' or '.join(accepted), where)))
    elif not all(in_topics.values()):
        lack = [s for s in (s1, s2) if not in_topics[s]]
        c2.set(False, reason('узел %s не подписан на топики узла %s' % (comp, ', '.join(lack)),
                             'node %s does not subscribe to a topic of %s' % (comp, ', '.join(lack))))
    else:
        c2.set(True, reason('%s публикует %s, слушает %s' % (comp, res_topic, ', '.join(in_topics[s1] + in_topics[s2])),
                            '%s publishes %s, subscribes to %s'
                            % (comp, res_topic, ', '.join(in_topics[s1] + in_topics[s2]))))
    return res_topic, in_topics


def judge_values(c3, obs, isu, res_topic, in_topics):
    """Criterion 3: every judged result equals the operation on its operands (one reading)."""
    _, (s1, s2), _ = roles(isu)
    ops = operations(isu)
    msgs = obs.get('msgs', {})
    results = msgs.get(res_topic, []) if res_topic else []
    if not res_topic:
        return c3.set(False, reason('нет топика результата', 'no result topic'))
    if not results:
        return c3.set(False, reason('на %s не пришло ни одного числа' % res_topic,
                                    'no number arrived on %s' % res_topic))
    if not all(in_topics.values()):
        return c3.set(False, reason('неизвестно, откуда берутся операнды', 'cannot tell where the operands come from'))
    first = sorted(v for t in in_topics[s1] for v in msgs.get(t, []))
    second = sorted(v for t in in_topics[s2] for v in msgs.get(t, []))
    int_result = obs.get('types', {}).get(res_topic, '').split('/')[-1].lower().startswith(('int', 'uint'))
    # every reading of the variant's row is tried; the one with the fewest wrong results
    # judges (the printed one on a tie), so a solution follows one reading throughout
    tried = [(op,) + match_results(results, first, second, op, int_result) for op in ops]
    op, verified, wrong, ex = min(tried, key=lambda m: m[2])
    if wrong:
        r, a, b, _ = ex
        want = ['%s %s %s = %s %s %s = %s' % (s1, o, s2, fmt(a), o, fmt(b), fmt(apply_op(o, a, b))) for o in ops]
        alt_ru = ' (строка варианта читается по-разному; годится любое из прочтений)' if len(ops) > 1 else ''
        alt_en = ' (the row reads two ways; either reading passes)' if len(ops) > 1 else ''
        return c3.set(False, reason('результат %s, а %s (неверно %d из %d; '
                                    'проверены все операнды за %.0f с до и %.0f с после каждого результата)%s'
                                    % (fmt(r), ' или '.join(want), wrong, verified, WINDOW, LAG, alt_ru),
                                    'result %s but %s (%d of %d wrong; '
                                    'every operand from %.0f s before to %.0f s after each result was tried)%s'
                                    % (fmt(r), ' or '.join(want), wrong, verified, WINDOW, LAG, alt_en)))
    if verified < MIN_RESULTS:
        return c3.set(False, reason('удалось сверить лишь %d результатов (нужно %d)' % (verified, MIN_RESULTS),
                                    'only %d results could be checked against their operands (%d needed)'
                                    % (verified, MIN_RESULTS)))
    formula = '%s %s %s' % (s1, op, s2)
    other = ' '.join(o for o in ops if o != op)
    alt_ru = ' (годится и прочтение %s)' % other if other else ''
    alt_en = ' (the reading %s passes too)' % other if other else ''
    return c3.set(True, reason('%d из %d результатов верны: %s%s' % (verified, verified, formula, alt_ru),
                               '%d of %d results correct: %s%s' % (verified, verified, formula, alt_en)))


def judge_rate(c4, obs, res_topic):
    """Criterion 4: at least MIN_RESULTS results, no pause over MAX_GAP (receive times)."""
    results = obs.get('msgs', {}).get(res_topic, []) if res_topic else []
    if not res_topic or not results:
        return c4.set(False, reason('результат не публикуется', 'the result is not published'))
    ts = [t for t, _ in results]
    gaps = [b - a for a, b in zip(ts, ts[1:])]
    end = obs.get('end', ts[-1])
    gap = max(gaps + [end - ts[-1]])
    first_after = ts[0] - obs.get('start', ts[0])
    if len(ts) < MIN_RESULTS:
        return c4.set(False, reason('за %.0f с пришло %d сообщений (нужно ≥ %d)' % (OBSERVE, len(ts), MIN_RESULTS),
                                    '%d messages in %.0f s (>= %d needed)' % (len(ts), OBSERVE, MIN_RESULTS)))
    if gap > MAX_GAP:
        return c4.set(False, reason('пауза %.1f с между результатами '
                                    '(допустимо %.0f с; по времени приёма у проверяющего)'
                                    % (gap, MAX_GAP),
                                    'a %.1f s pause between results (%.0f s allowed; by the grader\'s receive times)'
                                    % (gap, MAX_GAP)))
    rate = (len(ts) - 1) / (ts[-1] - ts[0]) if ts[-1] > ts[0] else 0.0
    return c4.set(True, reason('%d сообщений, %.1f Гц, первое через %.1f с' % (len(ts), rate, first_after),
                               '%d messages, %.1f Hz, first after %.1f s' % (len(ts), rate, first_after)))


def evaluate(obs):
    """Criteria from an observation dict (see grading.lab1.observer.Lab1Observer.run)."""
    isu = obs['isu']
    c = criteria_by_id(CRITERIA)
    judge_nodes(c['1'], obs)
    res_topic, in_topics = judge_topics(c['2'], obs, isu)
    judge_values(c['3'], obs, isu, res_topic, in_topics)
    judge_rate(c['4'], obs, res_topic)
    return [c[i] for i in '1234']
