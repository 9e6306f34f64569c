"""The demo's per-phase real-time factor and stack CPU (space_scanner_bringup.pace) on a fake
/proc and fake clocks (no master, no simulation)."""
import math
import os

import pytest

from space_scanner_bringup import pace

TICK = os.sysconf('SC_CLK_TCK')


def write_proc(root, pid, ppid, comm, cpu_s, argv):
    d = root / str(pid)
    d.mkdir(exist_ok=True)
    ticks = int(round(cpu_s * TICK))
    # pid (comm) state ppid pgrp session tty tpgid flags minflt cminflt majflt cmajflt utime stime
    fields = ['S', str(ppid)] + ['0'] * 9 + [str(ticks - ticks // 2), str(ticks // 2)] + ['0'] * 5
    (d / 'stat').write_text('%d (%s) %s\n' % (pid, comm, ' '.join(fields)))
    (d / 'cmdline').write_bytes(b'\0'.join(a.encode() for a in argv) + b'\0')


def launch_tree(root, cpu):
    """roslaunch 10 -> sim_node 11 (with a space and parentheses in its comm), move_base 12 ->
    a helper 13; an unrelated process 20."""
    write_proc(root, 10, 1, 'roslaunch', cpu[10], ['/usr/bin/python3', '/usr/bin/roslaunch', 'x'])
    write_proc(root, 11, 10, 'sim (node)', cpu[11],
               ['/usr/bin/python3', '/ws/devel/lib/ode_sim/sim_node', '__name:=gazebo'])
    write_proc(root, 12, 10, 'move_base', cpu[12], ['/ws/lib/move_base', '__name:=move_base'])
    write_proc(root, 13, 12, 'sh', cpu[13], ['/bin/sh', '-c', 'true'])
    write_proc(root, 20, 1, 'other', cpu[20], ['/usr/bin/other'])


def test_process_tree_cpu_names_nodes_and_sums_descendants(tmp_path):
    launch_tree(tmp_path, {10: 0.5, 11: 12.0, 12: 3.0, 13: 0.25, 20: 99.0})
    tree = pace.process_tree_cpu(10, proc=str(tmp_path))
    assert set(tree) == {10, 11, 12, 13}            # not the unrelated process
    assert tree[11] == ('gazebo', pytest.approx(12.0))
    assert tree[12] == ('move_base', pytest.approx(3.0))
    assert tree[10][0] == 'roslaunch' and tree[13][0] == 'sh'
    assert pace.process_tree_cpu(99, proc=str(tmp_path)) == {}


def test_phase_meter_rtf_and_cpu_per_simulated_second(tmp_path):
    clock = {'sim': 100.0, 'wall': 1000.0}
    launch_tree(tmp_path, {10: 0.5, 11: 12.0, 12: 3.0, 13: 0.25, 20: 0.0})
    meter = pace.PhaseMeter(lambda: clock['sim'], lambda: clock['wall'],
                            lambda r: pace.process_tree_cpu(r, proc=str(tmp_path)))
    meter.start(10)
    # 60 simulated s in 75 wall s; the simulator used 18 CPU s, move_base 6, a new node 3
    clock['sim'], clock['wall'] = 160.0, 1075.0
    launch_tree(tmp_path, {10: 0.5, 11: 30.0, 12: 9.0, 13: 0.25, 20: 50.0})
    write_proc(tmp_path, 14, 10, 'amcl', 3.0, ['/ws/lib/amcl', '__name:=amcl'])
    f = meter.figures()
    assert f['sim_s'] == pytest.approx(60.0) and f['wall_s'] == pytest.approx(75.0)
    assert f['rtf'] == pytest.approx(0.8)
    assert f['cpu_s'] == pytest.approx(27.0)
    assert f['cpu_per_sim_s'] == pytest.approx(27.0 / 60.0)
    assert [n for n, _ in f['top'][:3]] == ['gazebo', 'move_base', 'amcl']
    line = pace.describe('exploration', f)
    assert line.startswith('exploration: 0.80x real time (60 s simulated in 75 s of wall time)')
    assert 'the stack 0.45 CPU s per simulated s (gazebo 0.30, move_base 0.10, amcl 0.05' in line
    # an interval from an earlier point: 40 simulated s in 40 wall s, 4 CPU s
    clock['sim'], clock['wall'] = 200.0, 1115.0
    launch_tree(tmp_path, {10: 0.5, 11: 34.0, 12: 9.0, 13: 0.25, 20: 50.0})
    g = meter.figures(f['point'])
    assert g['rtf'] == pytest.approx(1.0) and g['cpu_per_sim_s'] == pytest.approx(0.1)


def test_phase_meter_without_simulated_time_reports_no_cpu_ratio():
    meter = pace.PhaseMeter(lambda: 5.0, iter([0.0, 2.0]).__next__, lambda r: {})
    meter.start(1)
    f = meter.figures()
    assert f['rtf'] == 0.0 and math.isnan(f['cpu_per_sim_s'])
    assert 'nan CPU s per simulated s' in pace.describe('stalled', f)
