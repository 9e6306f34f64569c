"""The grading sandbox under labs/grade: adversarial lab 2 submissions fail with the right
reason, the reference passes, and the course tree is byte-for-byte unchanged afterwards."""
import os

import pytest

from grading import adversarial, sandbox
from grading.selftest import crit, failed, run_cases

CASES = dict({'reference': ('123451', {})},
             **{name: ('123451', kw) for name, kw in adversarial.recipes().items()})


@pytest.fixture(scope='module')
def tree_before():
    return adversarial.tree_digest()


@pytest.fixture(scope='module')
def runs(tree_before, tmp_path_factory):
    why = sandbox.probe()
    assert why is None, 'no grading sandbox can be made on this machine: %s' % why
    return run_cases('lab2', CASES, str(tmp_path_factory.mktemp('sbx')), workers=2)


def lab_failed(crits):
    return [c for c in failed(crits) if c != '0']


def test_reference_passes(runs):
    rc, out, crits = crit(runs, 'reference')
    assert rc == 0 and not failed(crits), out
    assert '(sandboxed)' in out and 'self-check' not in out, out


def test_forge_kill_gets_nothing(runs):
    rc, out, crits = crit(runs, 'forge_kill')
    # the report path and the checker are out of its reach: it is graded on its (no) lab work
    assert rc == 1 and crits['0'][0] and {'1', '2', '3'} <= set(lab_failed(crits)), out
    assert 'roslaunch' in crits['1'][1], out
    assert 'tampering' not in out, out


def test_cmake_writes_fail_to_build(runs):
    rc, out, crits = crit(runs, 'cmake_writes')
    assert rc == 1 and not crits['0'][0], out
    assert 'does not build' in crits['0'][1] and 'pwned_by_student.txt' in crits['0'][1], out
    for rel in adversarial.PWNED:
        assert not os.path.exists(os.path.join(adversarial.REPO, rel)), rel


def test_copy_of_reference_is_not_graded(runs):
    rc, out, crits = crit(runs, 'copies_reference')
    assert rc == 1 and crits['0'][0] and '1' in failed(crits), out
    assert 'roslaunch' in crits['1'][1] and '2' in failed(crits), out


def test_rosnode_kill_is_tampering(runs):
    rc, out, crits = crit(runs, 'rosnode_kill')
    assert rc == 1 and crits['0'][0] and lab_failed(crits) == ['1', '2', '3', '4', '5', '6'], out
    for cid in '123456':
        assert crits[cid][1].startswith('tampering: the checker was shut down through the ROS API'), crits[cid]
    assert 'external shutdown request from [/rosnode]' in crits['1'][1], crits['1']


def test_fork_bomb_stopped(runs):
    rc, out, crits = crit(runs, 'fork_bomb')
    assert rc == 1 and crits['0'][0], out
    assert 'the sandbox reached its process limit' in crits['1'][1], out


def test_fill_disk_bounded(runs):
    rc, out, crits = crit(runs, 'fill_disk')
    assert rc == 1 and crits['0'][0], out
    assert 'No space left on device' in crits['1'][1] or 'Read-only file system' in crits['1'][1], out


def test_course_tree_unchanged(runs, tree_before):
    after = adversarial.tree_digest()
    changed = sorted(p for p in set(after) | set(tree_before) if after.get(p) != tree_before.get(p))
    assert not changed, changed


@pytest.mark.full
def test_no_sandbox_agrees(tmp_path):
    """--no-sandbox (today's path) and the sandbox give the same verdicts on the references and
    the seeded faults of lab 2 (every criterion's pass/fail)."""
    from importlib import util
    spec = util.spec_from_file_location('lab2_cases', os.path.join(os.path.dirname(__file__), 'test_lab2_grader.py'))
    mod = util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    both = {}
    for mode, args in (('sandbox', ()), ('plain', ('--no-sandbox',))):
        res = run_cases('lab2', mod.CASES, str(tmp_path / mode), workers=2, args=args)
        both[mode] = {n: (r[0], {c: p for c, (p, _w) in r[2].items()}) for n, r in res.items()}
    assert both['sandbox'] == both['plain']
