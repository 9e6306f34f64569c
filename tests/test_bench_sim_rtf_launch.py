"""bench/sim_rtf --launch's helpers without a roscore: the process tree and thread figures it
reads from /proc, and the report's ratios and stamp counts."""
import os
import subprocess
import sys

HERE = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), 'bench',
                    'sim_rtf.d')
sys.path.insert(0, HERE)

import launch_mode  # noqa: E402


def test_tree_names_nodes_by_their_name_argument():
    child = subprocess.Popen([sys.executable, '-c', 'import time; time.sleep(60)',
                              '__name:=probe_node'])
    try:
        procs = launch_mode.tree(os.getpid())
        assert procs[child.pid][0] == 'probe_node'
        assert os.getpid() in procs
        assert all(cpu >= 0.0 for _, cpu in procs.values())
        assert launch_mode.find_sim_node(procs) is None
        procs[child.pid] = ('gazebo', 0.0)
        assert launch_mode.find_sim_node(procs) == child.pid
    finally:
        child.kill()
        child.wait()


def test_threads_have_cpu_and_schedstat():
    th = launch_mode.threads(os.getpid())
    comm, cpu, run, wait = (th[os.getpid()][0], th[os.getpid()][1]) + th[os.getpid()][2]
    assert comm and cpu >= 0.0 and run > 0 and wait >= 0


def test_report_ratios_and_stamps():
    m = {'sim': 100.0, 'wall': 10.0, 'shipped_rate': 1000.0, 'load': 1.0, 'sim_pid': 1,
         'procs': {1: ('gazebo', 4.0), 2: ('robot_state_publisher', 1.0)},
         'threads': {1: ('sim_node', 3.0, 6e9, 1e9), 7: ('sim_node', 1.0, 1e9, 0)},
         'stats': {'clock': 500, 'tf': {'/robot_state_publisher': [200, 1000]},
                   'sensors': {'/diffrobot/joint_states': {'received': 12, 'first': 1.0,
                                                           'last': 1.2, 'distinct': 11}}},
         'warn': []}
    text = '\n'.join(launch_mode.report('pw5', m, 20.0, 40.0))
    assert '10.00x real time over 10.0 wall s = 0.50 of the bare C loop (20.0x' in text
    assert 'per CPU second of the whole launch 20.00x = 0.50 of bare C per CPU second' in text
    assert 'on CPU 60 %, runnable waiting for a CPU 10 %, blocked (lockstep / locks / GIL / ' \
           'sleeps) 30 %' in text
    assert '/clock: 500 messages = 5 per simulated s, 50 per wall s' in text
    assert '/tf from /robot_state_publisher: 200 messages (2 per simulated s), 1000' in text
    # 11 distinct stamps over 0.2 s at a set 50 Hz: exact, one duplicate
    assert '50.00 Hz by header stamps (set 50, +0.00 %), 11 of 11 stamps, 1 duplicates' in text
