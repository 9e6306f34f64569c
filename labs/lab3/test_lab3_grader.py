"""Lab 3 grader self-tests: the reference passes, seeded faults fail the right criterion."""
import pytest

from grading.selftest import crit, failed, run_cases

MODEL = 'urdf/my_robots_super_model.xacro'
LAUNCH = 'launch/lab3_setup.launch'
ROW1 = "dict(links=5,  arm='RRRR', wheels='CC',   body=[0.200, 0.140, 0.090])"
CASES = {
    'ref_v1': ('123451', {}),
    'ref_v4': ('334404', {}),
    'wrong_joint_type': ('123451', {'edits': [(MODEL, ROW1, ROW1.replace("'RRRR'", "'RRRC'"))]}),
    'missing_inertial': ('123451', {'edits': [(MODEL, '<xacro:inertial_box mass="1.0" x="${L}" y="${W}" z="${H}"/>',
                                               '')]}),
    'wrong_size': ('123451', {'edits': [(MODEL, ROW1, ROW1.replace('0.140', '0.150'))]}),
    'no_robot_state_publisher': ('123451', {'edits': [(
        LAUNCH, '<node name="robot_state_publisher" pkg="robot_state_publisher" type="robot_state_publisher"/>', '')]}),
    'malformed_xacro': ('123451', {'edits': [(MODEL, '</robot>', '')]}),
}


@pytest.fixture(scope='module')
def runs(tmp_path_factory):
    return run_cases('lab3', CASES, str(tmp_path_factory.mktemp('lab3')), workers=4)


@pytest.mark.parametrize('name', ['ref_v1', 'ref_v4'])
def test_reference_passes(runs, name):
    rc, out, crits = crit(runs, name)
    assert rc == 0, out
    assert sorted(crits) == ['0', '1', '2', '3', '4', '5', '6', '7'] and not failed(crits), out


def test_reference_v4_has_a_caster(runs):
    _, out, crits = crit(runs, 'ref_v4')
    assert 'caster_joint S' in crits['4'][1] and '260x160x100 mm' in crits['5'][1], out


def test_wrong_joint_type(runs):
    rc, out, crits = crit(runs, 'wrong_joint_type')
    assert rc == 1 and failed(crits) == ['3'], out
    assert 'manipulator RRRC' in crits['3'][1] and 'arm_joint_4 continuous' in crits['3'][1]
    assert 'the variant wants RRRR' in crits['3'][1]


def test_missing_inertial(runs):
    rc, out, crits = crit(runs, 'missing_inertial')
    assert rc == 1 and failed(crits) == ['6'], out
    assert crits['6'][1] == 'link base_link: no <inertial>'


def test_wrong_size(runs):
    rc, out, crits = crit(runs, 'wrong_size')
    assert rc == 1 and failed(crits) == ['5'], out
    assert 'body base_link: 200x150x90 mm, the variant wants 200x140x90 mm' in crits['5'][1]


def test_launch_without_robot_state_publisher(runs):
    rc, out, crits = crit(runs, 'no_robot_state_publisher')
    assert rc == 1 and failed(crits) == ['7'], out
    assert 'no robot_state_publisher node is running' in crits['7'][1]
    assert 'no TF for links: arm_link_1' in crits['7'][1]


def test_malformed_xacro(runs):
    rc, out, crits = crit(runs, 'malformed_xacro')
    assert rc == 1 and failed(crits) == ['1', '2', '3', '4', '5', '6', '7'], out
    assert crits['0'][0]
    assert crits['1'][1].startswith('xacro: ') and 'not checked' in crits['2'][1]


@pytest.mark.full
def test_reference_all_variants(tmp_path):
    cases = {'v%d' % d: ('12345%d' % d, {}) for d in range(10)}
    res = run_cases('lab3', cases, str(tmp_path), workers=3)
    bad = {n: r[1][-2000:] for n, r in res.items() if r[0] != 0}
    assert not bad, bad


@pytest.mark.full
def test_starter_is_not_a_solution(tmp_path):
    res = run_cases('lab3', {'starter': ('123456', {'source': 'starter'})}, str(tmp_path))
    rc, out, crits = res['starter']
    assert rc == 1 and crits['0'][0], out
    assert 'no file urdf/my_robots_super_model.xacro in package my_firts_robot_model' in crits['1'][1]
    assert 'launch/lab3_setup.launch not found' in crits['7'][1]
