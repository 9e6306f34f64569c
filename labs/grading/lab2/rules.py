"""Lab 2 rules: two turtlesims in ns1_<ISU>/ns2_<ISU>, the points, the time, the follower.

Pure logic: the path geometry and `evaluate(obs)` that turns an observation
(grading.lab2.observer) into the six criteria. No rospy here.
"""
import math

from grading.common import criteria_by_id, reason
from grading.lab2.criteria import CRITERIA
from grading.lab2.variants import namespaces, points, printed_points

POINT_TOL = 0.3        # m: turtle 1 must come this close to every point
FOLLOW_TOL = 0.5       # m: symmetric max nearest-point distance between the two paths
T2_POINT_TOL = 0.5     # m: turtle 2 must come this close to every point
TIME_ABS_TOL = 1.5     # s: |reported - observed| <= TIME_ABS_TOL + TIME_REL_TOL * observed
TIME_REL_TOL = 0.10
RUN_LIMIT = 300.0      # s: the whole run, from roslaunch to both turtles at rest
STILL_TIME = 6.0       # s: both turtles at rest this long = the run is over
NO_MOTION_LIMIT = 90.0  # s: turtle 1 never moving this long after start = give up (generous: start-up
# of two turtlesims and a controller on a loaded machine)
MOVE_EPS = 0.02        # m: a pose change above this is motion
WALL_MARGIN = 0.02     # m: a pose this close to the 0..11.09 border is a wall hit
WORLD = 11.088889
ALLOWED_GLOBAL = ('/rosout', '/rosout_agg', '/clock')


# --- path geometry ------------------------------------------------------------------------

def first_motion(path, eps=MOVE_EPS):
    """Index of the first pose (t, x, y[, theta]) that moved more than eps or turned more
    than 0.05 rad from the first one, or None."""
    if not path:
        return None
    x0, y0 = path[0][1], path[0][2]
    th0 = path[0][3] if len(path[0]) > 3 else 0.0
    for i, p in enumerate(path):
        turned = abs(math.atan2(math.sin(p[3] - th0), math.cos(p[3] - th0))) if len(p) > 3 else 0.0
        if math.hypot(p[1] - x0, p[2] - y0) > eps or turned > 0.05:
            return i
    return None


def visits(path, pts, tol):
    """{point: (closest distance, time first within tol or None)}."""
    out = {}
    for q in pts:
        best, when = math.inf, None
        for t, x, y in ((p[0], p[1], p[2]) for p in path):
            d = math.hypot(x - q[0], y - q[1])
            best = min(best, d)
            if when is None and d <= tol:
                when = t
        out[q] = (best, when)
    return out


def arrivals(path, q, tol, leave=None):
    """Times the path arrives within tol of q, each after having left it (farther than
    `leave`, default 2 * tol) since the previous arrival."""
    leave = 2 * tol if leave is None else leave
    out, away = [], True
    for p in path:
        d = math.hypot(p[1] - q[0], p[2] - q[1])
        if away and d <= tol:
            out.append(p[0])
            away = False
        elif d > leave:
            away = True
    return out


def row_time(path, row, tol):
    """When the path has visited the row as printed, a point printed k times being arrived at
    k separate times (the reading of a repeated cell as one more visit); None if it never has."""
    done = 0.0
    for q in set(row):
        times = arrivals(path, q, tol)
        k = row.count(q)
        if len(times) < k:
            return None
        done = max(done, times[k - 1])
    return done


def densify(path, step=0.05):
    pts = []
    for a, b in zip(path, path[1:]):
        (x0, y0), (x1, y1) = (a[1], a[2]), (b[1], b[2])
        n = max(1, int(math.hypot(x1 - x0, y1 - y0) / step))
        pts += [(x0 + (x1 - x0) * k / n, y0 + (y1 - y0) * k / n) for k in range(n)]
    if path:
        pts.append((path[-1][1], path[-1][2]))
    return pts


def _directed(a, b):
    """max over a of the distance to the nearest point of b (grid-bucketed)."""
    cell = 0.5
    grid = {}
    for x, y in b:
        grid.setdefault((int(x // cell), int(y // cell)), []).append((x, y))
    worst = 0.0
    for x, y in a:
        best = math.inf
        r = 1
        while best == math.inf or (r - 1) * cell < best:
            cx, cy = int(x // cell), int(y // cell)
            for i in range(cx - r, cx + r + 1):
                for j in range(cy - r, cy + r + 1):
                    for qx, qy in grid.get((i, j), ()):
                        best = min(best, math.hypot(qx - x, qy - y))
            r += 1
            if r > 40:
                break
        worst = max(worst, best)
    return worst


def path_deviation(p1, p2):
    """Symmetric max nearest-point distance (Hausdorff) between two pose paths, m."""
    a, b = densify(p1), densify(p2)
    if not a or not b:
        return math.inf
    return max(_directed(a, b), _directed(b, a))


def path_length(path):
    return sum(math.hypot(b[1] - a[1], b[2] - a[2]) for a, b in zip(path, path[1:]))


def wall_hits(path):
    return [p for p in path if min(p[1], p[2]) <= WALL_MARGIN or max(p[1], p[2]) >= WORLD - WALL_MARGIN]


def under(name, spaces):
    return any(name == s or name.startswith(s + '/') for s in spaces)


def fmt_pt(q):
    return '(%g,%g)' % q


def judge_sims(c1, obs, ns1, ns2):
    """Criterion 1: a turtlesim publishes turtle1's pose in each namespace."""
    pubs = obs.get('pubs', {})
    missing = []
    for ns, path in ((ns1, obs.get('pose1', [])), (ns2, obs.get('pose2', []))):
        topic = ns + '/turtle1/pose'
        if not any(topic in ts for ts in pubs.values()) or not path:
            missing.append(topic)
    launch_err = obs.get('launch_error')
    if launch_err:
        return c1.set(False, reason('roslaunch: %s' % launch_err, 'roslaunch: %s' % launch_err))
    if missing:
        return c1.set(False, reason('никто не публикует %s' % ', '.join(missing),
                                    'nobody publishes %s' % ', '.join(missing)))
    sims = sorted(n for n, ts in pubs.items() if ns1 + '/turtle1/pose' in ts or ns2 + '/turtle1/pose' in ts)
    return c1.set(True, reason('turtlesim: %s' % ', '.join(sims), 'turtlesim: %s' % ', '.join(sims)))


class Route:
    """Turtle 1's run against the variant's points: first motion, visits, when it was done."""

    def __init__(self, p1, pts):
        self.i1 = first_motion(p1)
        self.v1 = visits(p1, pts, POINT_TOL)
        self.miss = [q for q in pts if self.v1[q][1] is None]
        self.t_start = p1[self.i1][0] if self.i1 is not None else None
        self.t_done = max(self.v1[q][1] for q in pts) if not self.miss and pts else None


def judge_points(c2, p1, pts, r):
    """Criterion 2: turtle 1 visits every point."""
    v1 = r.v1
    if not p1:
        return c2.set(False, reason('нет поз черепахи 1', 'no pose of turtle 1 was received'))
    if r.i1 is None:
        return c2.set(False, reason('черепаха 1 не двигалась', 'turtle 1 never moved'))
    if r.miss:
        return c2.set(False, reason('пропущены точки: %s'
                                    % ', '.join('%s (ближе всего %.2f м)' % (fmt_pt(q), v1[q][0]) for q in r.miss),
                                    'points missed: %s'
                                    % ', '.join('%s (closest %.2f m)' % (fmt_pt(q), v1[q][0]) for q in r.miss)))
    order = sorted(pts, key=lambda q: v1[q][1])
    txt = ', '.join('%s %.2f m @%.1f s' % (fmt_pt(q), v1[q][0], v1[q][1] - r.t_start) for q in order)
    return c2.set(True, reason('пройдены (допуск %.1f м): %s'
                               % (POINT_TOL, txt.replace(' m ', ' м ').replace(' s', ' с')),
                               'visited (tolerance %.1f m): %s' % (POINT_TOL, txt)), order=[list(q) for q in order])


def judge_time(c3, obs, isu, r):
    """Criterion 3: the time on result_<ISU> is the time to the last point (or, for a row
    printing a point twice, to the arrival there again)."""
    pts, row, p1 = points(isu), printed_points(isu), obs.get('pose1', [])
    results = obs.get('results', {})
    named = sorted(t for t in results if t.endswith('/result_' + isu))
    got = [(t, s[-1][1]) for t, s in sorted(results.items()) if t in named and s]
    observed = (r.t_done - r.t_start) if r.t_done is not None else None
    # a row printing a point twice also reads "visit it again": the time to that arrival passes too
    t_row = row_time(p1, row, POINT_TOL) if (r.t_done is not None and len(row) > len(pts)) else None
    again = (t_row - r.t_start) if t_row is not None and t_row > r.t_done else None
    if not named:
        return c3.set(False, reason('нет топика, оканчивающегося на result_%s' % isu,
                                    'no topic ending in result_%s' % isu))
    if not got:
        return c3.set(False, reason('в %s ничего не опубликовано' % named[0], 'nothing was published on %s' % named[0]))
    if observed is None:
        return c3.set(False, reason('черепаха 1 не прошла все точки: время не с чем сравнить',
                                    'turtle 1 did not visit every point: nothing to compare the time with'))
    topic, reported = got[0]
    tol = TIME_ABS_TOL + TIME_REL_TOL * observed
    rep_txt = ', '.join(fmt_pt(q) for q in pts if row.count(q) > 1)
    match, by_row = (observed if abs(reported - observed) <= tol else None), False
    if match is None and again is not None and abs(reported - again) <= TIME_ABS_TOL + TIME_REL_TOL * again:
        match, by_row = again, True
    if match is None:
        also_ru = also_en = ''
        if again is not None:
            also_ru = ' или %.2f с до повторного заезда в %s (строка, как напечатана)' % (again, rep_txt)
            also_en = ' or %.2f s to the repeated %s again (the row as printed)' % (again, rep_txt)
        return c3.set(False, reason('в %s %.2f с, а измерено %.2f с%s (допуск ±%.1f с; '
                                    'время измеряется от первого движения черепахи 1 до последней точки)'
                                    % (topic, reported, observed, also_ru, tol),
                                    '%s says %.2f s, measured %.2f s%s (tolerance ±%.1f s; '
                                    'timed from turtle 1\'s first motion to the last point)'
                                    % (topic, reported, observed, also_en, tol)))
    how_ru = ' (до повторного заезда в %s, строка как напечатана)' % rep_txt if by_row else ''
    how_en = ' (to the repeated %s again, the row as printed)' % rep_txt if by_row else ''
    return c3.set(True, reason('%s: %.2f с, измерено %.2f с%s' % (topic, reported, match, how_ru),
                               '%s: %.2f s, measured %.2f s%s' % (topic, reported, match, how_en)),
                  reported=reported, observed=match)


def judge_follow(c4, obs, ns1, ns2, pts, i1):
    """Criterion 4: turtle 2, driven from turtle 1's pose (no remap), repeats its path."""
    pubs, subs = obs.get('pubs', {}), obs.get('subs', {})
    p1, p2 = obs.get('pose1', []), obs.get('pose2', [])
    cmd2 = ns2 + '/turtle1/cmd_vel'
    pose1 = ns1 + '/turtle1/pose'
    drivers = sorted(n for n, ts in pubs.items() if cmd2 in ts)
    deaf = [n for n in drivers if pose1 not in subs.get(n, [])]
    rm = obs.get('remaps', [])
    i2 = first_motion(p2)
    v2 = visits(p2, pts, T2_POINT_TOL)
    miss2 = [q for q in pts if v2[q][1] is None]
    dev = path_deviation(p1[i1 - 1 if i1 else 0:], p2[i2 - 1 if i2 else 0:]) if (p1 and p2) else math.inf
    if rm:
        return c4.set(False, reason('remap запрещён: %s' % rm[0], 'remap is forbidden: %s' % rm[0]))
    if not drivers:
        return c4.set(False, reason('никто не публикует %s' % cmd2, 'nobody publishes %s' % cmd2))
    if deaf:
        return c4.set(False, reason('%s управляет черепахой 2, но не подписан на %s' % (deaf[0], pose1),
                                    '%s drives turtle 2 but does not subscribe to %s' % (deaf[0], pose1)))
    if i2 is None:
        return c4.set(False, reason('черепаха 2 не двигалась', 'turtle 2 never moved'))
    if dev > FOLLOW_TOL:
        return c4.set(False, reason('пути расходятся на %.2f м (допуск %.1f м)' % (dev, FOLLOW_TOL),
                                    'the paths differ by up to %.2f m (tolerance %.1f m)' % (dev, FOLLOW_TOL)))
    if miss2:
        return c4.set(False, reason('черепаха 2 не прошла %s' % ', '.join(fmt_pt(q) for q in miss2),
                                    'turtle 2 did not pass %s' % ', '.join(fmt_pt(q) for q in miss2)))
    return c4.set(True, reason('отклонение путей %.2f м (допуск %.1f м), ведёт %s'
                               % (dev, FOLLOW_TOL, ', '.join(drivers)),
                               'path deviation %.2f m (tolerance %.1f m), driven by %s'
                               % (dev, FOLLOW_TOL, ', '.join(drivers))),
                  deviation=dev)


def global_names(obs, spaces):
    """['node /x', 'topic /t (/node)', ...]: names of the graph outside the namespaces."""
    pubs, subs, srvs = obs.get('pubs', {}), obs.get('subs', {}), obs.get('srvs', {})
    bad = []
    for n in obs.get('nodes', []):
        if not under(n, spaces):
            bad.append('node %s' % n)
            continue
        for kind, table in (('topic', pubs), ('topic', subs), ('service', srvs)):
            for t in table.get(n, []):
                if not under(t, spaces) and t not in ALLOWED_GLOBAL:
                    bad.append('%s %s (%s)' % (kind, t, n))
    return sorted(set(bad))


def judge_names(c5, obs, ns1, ns2):
    """Criterion 5: no global names in the graph or the scripts."""
    bad = global_names(obs, (ns1, ns2))
    lits = obs.get('global_literals', [])
    if bad:
        return c5.set(False, reason('глобальное имя: %s' % bad[0]
                                    + (' и ещё %d' % (len(bad) - 1) if len(bad) > 1 else ''),
                                    'global name: %s' % bad[0]
                                    + (' and %d more' % (len(bad) - 1) if len(bad) > 1 else '')))
    if lits:
        return c5.set(False, reason('в скрипте глобальное имя: %s' % lits[0],
                                    'a script hardcodes a global name: %s' % lits[0]))
    if not obs.get('nodes'):
        return c5.set(False, reason('узлы не запустились', 'no node came up'))
    return c5.set(True, reason('узлов: %d, все имена внутри %s, %s' % (len(obs['nodes']), ns1, ns2),
                               '%d nodes, every name under %s, %s' % (len(obs['nodes']), ns1, ns2)))


def judge_run(c6, obs, r):
    """Criterion 6: the run ends within the limit, every point visited, no wall hit."""
    p1, p2 = obs.get('pose1', []), obs.get('pose2', [])
    walls = obs.get('wall_msgs', []) + ['%s at (%.2f, %.2f)' % (w, p[1], p[2])
                                        for w, path in (('turtle 1', p1), ('turtle 2', p2))
                                        for p in wall_hits(path)[:1]]
    end = obs.get('end_reason')
    dur = obs.get('duration', 0.0)
    if walls:
        return c6.set(False, reason('удар о стену: %s' % walls[0], 'hit a wall: %s' % walls[0]))
    if end == 'limit':
        return c6.set(False, reason('черепахи двигались дольше %.0f с (лимит времени проверки)' % RUN_LIMIT,
                                    'the turtles were still moving after %.0f s (the grader\'s time limit)'
                                    % RUN_LIMIT))
    if end == 'no_motion' or r.i1 is None:
        return c6.set(False, reason('черепаха 1 не двигалась %.0f с после запуска (лимит времени проверки)'
                                    % NO_MOTION_LIMIT,
                                    'turtle 1 did not move for %.0f s after the launch (the grader\'s time limit)'
                                    % NO_MOTION_LIMIT))
    if end == 'launch_exited':
        return c6.set(False, reason('roslaunch завершился раньше времени', 'roslaunch exited early'))
    if r.miss:
        return c6.set(False, reason('остановились, не пройдя все точки', 'stopped before visiting every point'))
    return c6.set(True, reason('всё завершено за %.1f с (лимит %.0f с), путь черепахи 1 %.1f м'
                               % (dur, RUN_LIMIT, path_length(p1)),
                               'all done in %.1f s (limit %.0f s), turtle 1 drove %.1f m'
                               % (dur, RUN_LIMIT, path_length(p1))))


def evaluate(obs):
    """The six criteria from an observation dict."""
    isu = obs['isu']
    ns1, ns2 = namespaces(isu)
    pts = points(isu)
    c = criteria_by_id(CRITERIA)
    p1 = obs.get('pose1', [])
    route = Route(p1, pts)
    judge_sims(c['1'], obs, ns1, ns2)
    judge_points(c['2'], p1, pts, route)
    judge_time(c['3'], obs, isu, route)
    judge_follow(c['4'], obs, ns1, ns2, pts, route.i1)
    judge_names(c['5'], obs, ns1, ns2)
    judge_run(c['6'], obs, route)
    return [c[i] for i in '123456']


def topic_owners(isu):
    """{observed topic: the service only its rightful publisher (that namespace's turtlesim)
    provides}: the checker fails every criterion as tampering when another node publishes it."""
    return {ns + '/turtle1/pose': ns + '/spawn' for ns in namespaces(isu)}
