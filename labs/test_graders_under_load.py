"""The graders on a machine made slow on purpose: every core kept busy by stress-ng while labs
1-3 grade their references (they must pass: a correct student's work never fails because the
machine is slow) and a seeded fault each (it must still fail, for the right reason). Two grades
run at once on top of the load, as on a student's laptop or a shared CI runner."""
import pytest

from course_testing import cpu_load
from grading.selftest import crit, failed, run_cases

LAB2_NODE = 'src/my_best_controller/node.py'
LAB3_MODEL = 'urdf/my_robots_super_model.xacro'
LAB3_ROW1 = "dict(links=5,  arm='RRRR', wheels='CC',   body=[0.200, 0.140, 0.090])"
CASES = {
    'lab1': {'ref': ('123456', {}), 'ref_div': ('334409', {}),
             'wrong_operation': ('123456', {'edits': [('src/my_robot_controller/numbers.py',
                                                       "'-': a - b", "'-': b - a")]})},
    'lab2': {'ref': ('123451', {}),
             'not_following': ('123451', {'edits': [(LAB2_NODE, "leader_ns = ns.replace('ns2_', 'ns1_', 1)",
                                                     'leader_ns = ns')]})},
    'lab3': {'ref': ('123451', {}),
             'wrong_size': ('123451', {'edits': [(LAB3_MODEL, LAB3_ROW1, LAB3_ROW1.replace('0.140', '0.150'))]})},
}
CRITERIA = {'lab1': 5, 'lab2': 7, 'lab3': 8}


@pytest.fixture(scope='module')
def runs(tmp_path_factory):
    out = {}
    with cpu_load():
        for lab, cases in CASES.items():
            out[lab] = run_cases(lab, cases, str(tmp_path_factory.mktemp(lab)), workers=2)
    return out


@pytest.mark.parametrize('lab,name', [('lab1', 'ref'), ('lab1', 'ref_div'), ('lab2', 'ref'), ('lab3', 'ref')])
def test_reference_passes_on_a_saturated_cpu(runs, lab, name):
    rc, out, crits = crit(runs[lab], name)
    assert rc == 0 and not failed(crits), out
    assert len(crits) == CRITERIA[lab], out


def test_seeded_faults_still_fail_for_their_reason(runs):
    rc, out, crits = crit(runs['lab1'], 'wrong_operation')
    assert rc == 1 and failed(crits) == ['3'], out
    assert 'node1 - node2' in crits['3'][1] and 'wrong' in crits['3'][1]
    rc, out, crits = crit(runs['lab2'], 'not_following')
    assert rc == 1 and failed(crits) == ['4'], out
    assert 'does not subscribe to /ns1_123451/turtle1/pose' in crits['4'][1]
    rc, out, crits = crit(runs['lab3'], 'wrong_size')
    assert rc == 1 and failed(crits) == ['5'], out
    assert 'the variant wants 200x140x90 mm' in crits['5'][1]
