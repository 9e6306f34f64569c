"""Unit tests of lab 2's rules (grading.lab2.rules) and package checks: no roscore."""
from grading.lab2 import package
from grading.lab2 import rules as lab2


def path(points, t0=0.0, dt=0.1, step=0.05):
    out, t = [], t0
    for (x0, y0), (x1, y1) in zip(points, points[1:]):
        n = max(1, int(((x1 - x0) ** 2 + (y1 - y0) ** 2) ** 0.5 / step))
        for k in range(n):
            out.append((t, x0 + (x1 - x0) * k / n, y0 + (y1 - y0) * k / n, 0.0))
            t += dt
    out.append((t, points[-1][0], points[-1][1], 0.0))
    return out


def test_path_geometry():
    a = path([(5.5, 5.5), (4, 2), (2, 3)])
    b = path([(5.5, 5.5), (4.2, 2.1), (2, 3)])
    assert lab2.path_deviation(a, a) < 0.06
    assert 0.15 < lab2.path_deviation(a, b) < 0.3
    v = lab2.visits(a, [(4, 2), (7, 1)], 0.3)
    assert v[(4, 2)][0] < 0.05 and v[(7, 1)][1] is None and v[(7, 1)][0] > 2
    assert lab2.first_motion([(0, 1, 1, 0), (1, 1, 1, 0.2)]) == 1
    assert lab2.wall_hits([(0, 0.0, 5, 0), (1, 5, 5, 0)]) == [(0, 0.0, 5, 0)]


def lab2_obs(p2_shift=0.0, isu='7772', route=((4, 2), (2, 3)), reported=None):
    """Turtle 1 drives `route` from the centre; turtle 2 the same (its first point shifted
    by p2_shift in x). ISU 7772: points (2,3) (4,2). The time published is `reported`, or
    0.3 s more than the time to the last point."""
    ns1, ns2 = '/ns1_' + isu, '/ns2_' + isu
    p1 = [(0.0, 5.544, 5.544, 0.0)] + path([(5.544, 5.544)] + list(route), t0=1.0)
    shifted = [(route[0][0] + p2_shift, route[0][1])] + list(route[1:])
    p2 = [(0.0, 5.544, 5.544, 0.0)] + path([(5.544, 5.544)] + shifted, t0=2.0)
    if reported is None:
        last = route[-1]
        reported = next(t for t, x, y, _ in p1 if abs(x - last[0]) < 0.3 and abs(y - last[1]) < 0.3) - p1[1][0] + 0.3
    n1, n2 = ns1 + '/c', ns2 + '/c'
    return {'isu': isu, 'remaps': [], 'global_literals': [], 'end_reason': 'still', 'duration': 30.0,
            'pose1': p1, 'pose2': p2, 'wall_msgs': [],
            'results': {ns1 + '/result_' + isu: [(50.0, reported)]},
            'nodes': [ns1 + '/sim', ns2 + '/sim', n1, n2],
            'pubs': {ns1 + '/sim': [ns1 + '/turtle1/pose', '/rosout'], ns2 + '/sim': [ns2 + '/turtle1/pose'],
                     n1: [ns1 + '/turtle1/cmd_vel', ns1 + '/result_' + isu], n2: [ns2 + '/turtle1/cmd_vel']},
            'subs': {n1: [ns1 + '/turtle1/pose'], n2: [ns2 + '/turtle1/pose', ns1 + '/turtle1/pose']},
            'srvs': {ns1 + '/sim': [ns1 + '/spawn']}}


def test_lab2_evaluate():
    ok = lab2.evaluate(lab2_obs())
    assert all(c.passed for c in ok), [c.reason['en'] for c in ok]
    off = lab2.evaluate(lab2_obs(p2_shift=1.0))
    assert not off[3].passed and 'paths differ' in off[3].reason['en']
    g = lab2_obs()
    g['pubs']['/ns1_7772/c'].append('/turtle1/cmd_vel')
    assert 'global name: topic /turtle1/cmd_vel' in lab2.evaluate(g)[4].reason['en']
    late = lab2_obs()
    late['results']['/ns1_7772/result_7772'] = [(50.0, 99.0)]
    assert 'measured' in lab2.evaluate(late)[2].reason['en'] and not lab2.evaluate(late)[2].passed
    noluanch = {'isu': '7772', 'launch_error': 'launch/lab2_setup.launch not found in package my_best_controller',
                'end_reason': 'launch_exited'}
    res = lab2.evaluate(noluanch)
    assert not any(c.passed for c in res) and 'not found' in res[0].reason['en']


def test_lab2_static_checks(tmp_path):
    pkg = tmp_path / 'p'
    (pkg / 'launch').mkdir(parents=True)
    (pkg / 'scripts').mkdir()
    (pkg / 'launch' / 'lab2_setup.launch').write_text(
        '<launch><arg name="isu" default="1"/><group ns="a"><node pkg="x" type="y" name="n" args="in:=out _p:=1">'
        '<remap from="a" to="b"/></node></group></launch>')
    (pkg / 'scripts' / 'c.py').write_text('"""/doc/string"""\nimport rospy\nrospy.Subscriber("/turtle1/pose", None)\n'
                                          'rospy.Publisher("cmd_vel", None)\nopen("/tmp/x")\n')
    assert package.declares_isu(package.find_launch(str(pkg)))
    r = package.remaps(str(pkg))
    assert len(r) == 2 and 'from="a" to="b"' in r[0] and 'in:=out' in r[1]
    assert package.global_literals(str(pkg)) == ['scripts/c.py:3 "/turtle1/pose"']


def lab2_obs_v9(route, reported_at):
    """ISU 7779 (row (2,3) (4,2) (7,1) (4,2)): turtle 1 drives `route`; the time published is
    that of its arrival at the end of leg `reported_at`, from the first motion."""
    p1 = [(0.0, 5.544, 5.544, 0.0)] + path([(5.544, 5.544)] + list(route), t0=1.0)
    ends, i = [], 1
    for q in route:       # path() puts each leg's end point exactly, in order
        while not (p1[i][1] == q[0] and p1[i][2] == q[1]):
            i += 1
        ends.append(p1[i][0])
        i += 1
    return lab2_obs(isu='7779', route=route, reported=ends[reported_at] - p1[1][0])


def test_lab2_row_9_as_printed():
    # the distinct printed points, time to the last of them: passes; (5,4) is not asked for
    once = lab2.evaluate(lab2_obs_v9([(4, 2), (2, 3), (7, 1)], 2))
    assert all(c.passed for c in once), [c.reason['en'] for c in once]
    assert 'visited (tolerance 0.3 m): (4,2)' in once[1].reason['en'] and '(5,4)' not in once[1].reason['en']
    # the repeated cell read as one more visit: back to (4,2), time to that arrival: passes
    again = lab2.evaluate(lab2_obs_v9([(2, 3), (4, 2), (7, 1), (4, 2)], 3))
    assert all(c.passed for c in again), [c.reason['en'] for c in again]
    assert 'to the repeated (4,2) again, the row as printed' in again[2].reason['en']
    # the same route, but the time of the first (7,1) arrival: passes too (first reading)
    assert lab2.evaluate(lab2_obs_v9([(2, 3), (4, 2), (7, 1), (4, 2)], 2))[2].passed
    # a time to neither: fails, naming both
    wrong = lab2.evaluate(lab2_obs_v9([(2, 3), (4, 2), (7, 1), (4, 2)], 0))[2]
    assert not wrong.passed and 'or ' in wrong.reason['en'] and 'to the repeated (4,2) again' in wrong.reason['en']
    # a row without a repeat has one reading: a later revisit does not change the time
    p = path([(5.5, 5.5), (4, 2), (2, 3), (4, 2)])
    v = lab2.visits(p, [(4.0, 2.0), (2.0, 3.0)], 0.3)
    assert lab2.row_time(p, [(4.0, 2.0), (2.0, 3.0)], 0.3) == v[(2.0, 3.0)][1] == max(w for _, w in v.values())


def test_lab2_arrivals_need_leaving():
    p = path([(5.5, 5.5), (4, 2), (4.2, 2.1), (4, 2), (2, 3), (4, 2)])
    times = lab2.arrivals(p, (4.0, 2.0), 0.3)
    assert len(times) == 2     # dithering within 0.6 m is one arrival; coming back from (2,3) is another
    assert lab2.row_time(p, [(4.0, 2.0), (2.0, 3.0), (4.0, 2.0)], 0.3) == times[1]
    assert lab2.row_time(p, [(4.0, 2.0)] * 3, 0.3) is None
