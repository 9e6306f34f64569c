"""sim_rtf --launch: the shipped launch files as a user runs them (headless), as fast as possible.

For each launch: roslaunch on a private roscore; once the robot's first sensor message is in,
`real_time_update_rate` 0 is set through /gazebo/set_physics_properties (as `gz physics -u 0`
does in Gazebo; the launch and world files stay as shipped); the robot drives; over the measured
window: sim seconds per wall second, per process CPU (every node of the launch, sim_node's
threads, the simulation thread's time off CPU), /clock and /tf publications, sensor rates by
header stamps. The window is cut into SEGMENTS parts; after each, the simulation is paused
(/gazebo/pause_physics: the launch's nodes idle) and the bare C ODE loop (bare_loop.c) steps
the same world and robot (the launch's robot_description) for a share of --bare-steps, in a
process and session of its own as the launch's nodes have (bare_worker.py), then the
simulation resumes: ours and bare C are measured interleaved,
under the same load of a shared machine, and the report gives ours / bare C by wall time and
per CPU second (the load-independent figure).
With paced=True (sim_rtf --launch --paced) the world keeps its shipped rate (1.0x real time
for the course's worlds), as `make demo` runs it: the report gives the achieved real-time factor
and the CPU seconds each process needs per simulated second (what 2 cores must supply)."""
import json
import os
import signal
import subprocess
import tempfile
import time

from space_scanner_bringup.pace import process_tree_cpu as tree, read_stat

HERE = os.path.dirname(os.path.abspath(__file__))

# name -> roslaunch arguments, world file (package, path), drive, {sensor topic: (type, Hz)}
LAUNCHES = {
    'simulation': {
        'args': ['space_scanner_simulation', 'simulation.launch', 'gui:=false', 'rviz:=false',
                 'teleop:=false'],
        'world': ('space_scanner_simulation', 'worlds/office.world'),
        'drive': 'twist:/diffbot_controller/cmd_vel',
        'sensors': {'/scan': ('sensor_msgs/LaserScan', 5.5),
                    '/imu/data_raw': ('sensor_msgs/Imu', 10.0),
                    '/diffbot_controller/odom': ('nav_msgs/Odometry', 50.0),
                    '/joint_states': ('sensor_msgs/JointState', 50.0)},
    },
    'navigation': {
        'args': ['space_scanner_bringup', 'navigation.launch', 'sim:=true'],
        'world': ('space_scanner_simulation', 'worlds/office.world'),
        'drive': 'twist:/diffbot_controller/cmd_vel',
        'sensors': {'/scan': ('sensor_msgs/LaserScan', 5.5),
                    '/imu/data_raw': ('sensor_msgs/Imu', 10.0),
                    '/diffbot_controller/odom': ('nav_msgs/Odometry', 50.0),
                    '/joint_states': ('sensor_msgs/JointState', 50.0),
                    '/odom': ('nav_msgs/Odometry', 30.0)},
    },
    # make demo's first phase: gmapping + move_base + explore_lite drive the robot themselves
    'explore': {
        'args': ['space_scanner_bringup', 'explore.launch', 'sim:=true'],
        'world': ('space_scanner_simulation', 'worlds/office.world'),
        'drive': 'none',
        'sensors': {'/scan': ('sensor_msgs/LaserScan', 5.5),
                    '/imu/data_raw': ('sensor_msgs/Imu', 10.0),
                    '/diffbot_controller/odom': ('nav_msgs/Odometry', 50.0),
                    '/joint_states': ('sensor_msgs/JointState', 50.0),
                    '/odom': ('nav_msgs/Odometry', 30.0)},
    },
    'pw5': {
        'args': ['my_robot_simulation_control', 'robot_sim_control.launch', 'gui:=false'],
        'world': ('my_robot_simulation_control', 'worlds/empty.world'),
        'drive': 'position:/diffrobot/joint1_position_controller/command,'
                 '/diffrobot/joint2_position_controller/command',
        'sensors': {'/diffrobot/joint_states': ('sensor_msgs/JointState', 50.0)},
    },
}

SEGMENTS = 4        # measured parts of the window, each followed by a bare C run


def threads(pid):
    """{tid: (comm, cpu s, (on-cpu ns, runqueue-wait ns))} of process `pid`."""
    out = {}
    for tid in os.listdir('/proc/%d/task' % pid):
        try:
            comm, _, cpu = read_stat('/proc/%d/task/%s/stat' % (pid, tid))
            with open('/proc/%d/task/%s/schedstat' % (pid, tid)) as f:
                run, wait = (int(x) for x in f.read().split()[:2])
        except (OSError, ValueError):
            continue
        out[int(tid)] = (comm, cpu, (run, wait))
    return out


def find_sim_node(procs):
    for pid, (name, _) in procs.items():
        if name == 'gazebo':
            return pid
    return None


def set_rate_zero():
    """real_time_update_rate 0 through the /gazebo API (the rest of the physics unchanged)."""
    import rospy
    from gazebo_msgs.srv import (GetPhysicsProperties, SetPhysicsProperties,
                                 SetPhysicsPropertiesRequest)
    rospy.wait_for_service('/gazebo/set_physics_properties', timeout=120)
    cur = rospy.ServiceProxy('/gazebo/get_physics_properties', GetPhysicsProperties)()
    req = SetPhysicsPropertiesRequest(time_step=cur.time_step, max_update_rate=0.0,
                                      gravity=cur.gravity, ode_config=cur.ode_config)
    res = rospy.ServiceProxy('/gazebo/set_physics_properties', SetPhysicsProperties)(req)
    if not res.success:
        raise SystemExit('sim_rtf --launch: set_physics_properties: %s' % res.status_message)
    return cur.max_update_rate


def shipped_rate_of():
    import rospy
    from gazebo_msgs.srv import GetPhysicsProperties
    rospy.wait_for_service('/gazebo/get_physics_properties', timeout=120)
    return rospy.ServiceProxy('/gazebo/get_physics_properties', GetPhysicsProperties)().max_update_rate


def wait_first(topic, typ, timeout):
    import rospy
    from roslib.message import get_message_class
    rospy.wait_for_message(topic, get_message_class(typ), timeout=timeout)


class BareWorker:
    """bare_worker.py on the launch's world and robot, in a session of its own as the launch."""

    def __init__(self, lib, cfg, urdf):
        self.proc = subprocess.Popen(
            ['/usr/bin/python3', os.path.join(HERE, 'bare_worker.py'), lib, world_path(cfg), urdf],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, start_new_session=True)
        if self.proc.stdout.readline().strip() != 'ready':
            raise SystemExit('sim_rtf --launch: the bare C worker did not start')

    def __call__(self, steps):
        self.proc.stdin.write('%d\n' % steps)
        self.proc.stdin.flush()
        wall, cpu = self.proc.stdout.readline().split()
        return float(wall), float(cpu)

    def close(self):
        self.proc.stdin.close()
        self.proc.wait(timeout=30)


def _call(name):
    import rospy
    from std_srvs.srv import Empty
    rospy.ServiceProxy(name, Empty)()


def measure_launch(name, seconds, warmup, tmp, paced=False, bare_lib=None, bare_steps=0):
    """Run one launch; returns a dict of the figures (and the robot_description file).
    With bare_lib (not paced): the bare C loop interleaved with the window (module doc)."""
    from course_testing import Proc, RosCore
    import rospy
    from gazebo_msgs.srv import GetWorldProperties
    cfg = LAUNCHES[name]
    core = RosCore()
    core.start()
    launch = listener = None
    try:
        env = core.env
        os.environ.update({k: v for k, v in env.items() if k.startswith('ROS_')})
        log = os.path.join(tmp, 'launch_%s.log' % name)
        launch = Proc(['roslaunch', '--wait'] + cfg['args'], env=env, log=log)
        rospy.init_node('sim_rtf_launch_bench', anonymous=True, disable_signals=True)
        first_topic, (first_type, _) = next(iter(cfg['sensors'].items()))
        listener = subprocess.Popen(
            ['/usr/bin/python3', os.path.join(HERE, 'launch_listener.py'), cfg['drive']] +
            ['%s=%s' % (t, ty) for t, (ty, _) in cfg['sensors'].items()], env=env,
            stdout=subprocess.PIPE, text=True, start_new_session=True)
        assert listener.stdout.readline().strip() == 'ready'
        for topic, (typ, _) in cfg['sensors'].items():      # controllers started, sensors on
            wait_first(topic, typ, 300)
        shipped_rate = shipped_rate_of() if paced else set_rate_zero()
        props = rospy.ServiceProxy('/gazebo/get_world_properties', GetWorldProperties)
        time.sleep(warmup)
        sim = find_sim_node(tree(launch.pid))
        if sim is None:
            raise SystemExit('sim_rtf --launch: no process named gazebo under roslaunch')
        urdf = os.path.join(tmp, '%s.urdf' % name)
        desc = rospy.get_param('/robot_description')
        open(urdf, 'w').write(desc)
        bare = BareWorker(bare_lib, cfg, urdf) if bare_lib and not paced else None
        segments = SEGMENTS if bare else 1
        listener.send_signal(signal.SIGUSR1)
        load = os.getloadavg()[0]
        sim_s = wall_s = 0.0
        procs, ths, bare_runs = {}, {}, []
        listener_cpu = 0.0
        listener_stat = '/proc/%d/stat' % listener.pid
        for _ in range(segments):
            s0, w0 = props().sim_time, time.monotonic()
            p0, t0, l0 = tree(launch.pid), threads(sim), read_stat(listener_stat)[2]
            time.sleep(seconds / segments)
            s1, w1 = props().sim_time, time.monotonic()
            p1, t1, l1 = tree(launch.pid), threads(sim), read_stat(listener_stat)[2]
            sim_s += s1 - s0
            wall_s += w1 - w0
            listener_cpu += l1 - l0
            for p, v in p1.items():
                if p in p0:
                    procs[p] = (v[0], procs.get(p, (v[0], 0.0))[1] + v[1] - p0[p][1])
            for k, v in t1.items():
                if k in t0:
                    old = ths.get(k, (v[0], 0.0, 0, 0))
                    ths[k] = (v[0], old[1] + v[1] - t0[k][1], old[2] + v[2][0] - t0[k][2][0],
                              old[3] + v[2][1] - t0[k][2][1])
            if bare:
                _call('/gazebo/pause_physics')
                time.sleep(0.2)         # the nodes settle (no /clock, no sensors)
                bare_runs.append(bare(max(1, bare_steps // segments)))
                _call('/gazebo/unpause_physics')
        if bare:
            bare.close()
        listener.send_signal(signal.SIGINT)
        stats = json.loads(listener.stdout.readline())
        listener.wait(timeout=30)
        warn = [l for l in launch.output().splitlines() if '[ERROR]' in l or 'WARN' in l]
        return {'sim': sim_s, 'wall': wall_s, 'shipped_rate': shipped_rate, 'load': load,
                'paced': paced, 'procs': procs, 'sim_pid': sim, 'threads': ths,
                'bare_runs': bare_runs, 'stats': stats, 'urdf': urdf, 'warn': warn,
                'listener_cpu': listener_cpu}
    finally:
        if listener is not None and listener.poll() is None:
            listener.kill()
            listener.wait()
        if launch is not None:
            launch.stop()
        core.stop()


def world_path(cfg):
    import rospkg
    pkg, rel = cfg['world']
    return os.path.join(rospkg.RosPack().get_path(pkg), rel)


def report(name, m, bare, bare_cpu):
    cfg = LAUNCHES[name]
    sim, wall = m['sim'], m['wall']
    rtf = sim / wall
    total_cpu = sum(c for _, c in m['procs'].values())
    cpu_rtf = sim / max(total_cpu, 1e-9)
    p = 'sim_rtf --launch %s:' % name
    if m.get('paced'):
        per_sim = total_cpu / max(sim, 1e-9)
        lines = ['%s roslaunch %s, paced as shipped (world rate %g): %.3fx real time over %.1f '
                 'wall s; the whole launch %.3f CPU s per simulated s (%.2f of the 2 cores at '
                 '1.0x real time)' % (p, ' '.join(cfg['args']), m['shipped_rate'], rtf, wall,
                                      per_sim, per_sim / 2.0)]
    else:
        lines = ['%s roslaunch %s (world rate %g set to 0 through /gazebo/set_physics_properties): '
                 '%.2fx real time over %.1f wall s = %.2f of the bare C loop (%.1fx, same world and '
                 'robot, this run, interleaved with ours: %s); per CPU second of the whole launch '
                 '%.2fx = %.2f of bare C per CPU second (%.1fx); sim_node alone per CPU second '
                 '%.2fx = %.2f'
                 % (p, ' '.join(cfg['args']), m['shipped_rate'], rtf, wall, rtf / bare, bare,
                    ' '.join('%.1fx' % r[0] for r in m.get('bare_runs', [])), cpu_rtf,
                    cpu_rtf / bare_cpu, bare_cpu, sim / max(m['procs'].get(m['sim_pid'],
                                                                           ('', 1e9))[1], 1e-9),
                    sim / max(m['procs'].get(m['sim_pid'], ('', 1e9))[1], 1e-9) / bare_cpu)]
    lines.append('%s CPU over the window: %.2f s for %.2f simulated s (%.2f CPU s per simulated '
                 's; load average %.1f on %d cores at its start); per process:'
                 % (p, total_cpu, sim, total_cpu / max(sim, 1e-9), m.get('load', 0.0),
                    os.cpu_count()))
    for pid, (pname, cpu) in sorted(m['procs'].items(), key=lambda kv: -kv[1][1]):
        lines.append('%s   %-28s %6.2f s  %5.1f %% of a core  %.3f CPU s per simulated s'
                     % (p, pname, cpu, 100.0 * cpu / wall, cpu / max(sim, 1e-9)))
    if 'listener_cpu' in m:
        lines.append('%s   (not the launch: the bench\'s listener, driving and counting: %.2f s, '
                     '%.1f %% of a core)' % (p, m['listener_cpu'], 100.0 * m['listener_cpu'] / wall))
    th = m['threads']
    main = th.get(m['sim_pid'])
    if main:
        run, wait = main[2] * 1e-9, main[3] * 1e-9
        lines.append('%s sim_node simulation thread: on CPU %.0f %%, runnable waiting for a CPU '
                     '%.0f %%, blocked (lockstep / locks / GIL / sleeps) %.0f %% of the window'
                     % (p, 100 * run / wall, 100 * wait / wall,
                        100 * max(0.0, wall - run - wait) / wall))
    others = sorted(((v[1], v[0], k) for k, v in th.items() if k != m['sim_pid']), reverse=True)
    lines.append('%s sim_node other threads: %d, %.2f CPU s; busiest: %s'
                 % (p, len(others), sum(o[0] for o in others),
                    ', '.join('%s/%d %.2f s' % (c, k, cpu) for cpu, c, k in others[:4])))
    st = m['stats']
    lines.append('%s /clock: %d messages = %.0f per simulated s, %.0f per wall s'
                 % (p, st['clock'], st['clock'] / max(sim, 1e-9), st['clock'] / wall))
    for caller, (msgs, tfs) in sorted(st['tf'].items(), key=lambda kv: -kv[1][0]):
        lines.append('%s /tf from %s: %d messages (%.0f per simulated s), %d transforms'
                     % (p, caller, msgs, msgs / max(sim, 1e-9), tfs))
    for topic, (_, hz) in cfg['sensors'].items():
        s = st['sensors'][topic]
        span = s['last'] - s['first']
        expected = int(round(span * hz)) + 1 if s['received'] else 0
        rate = (s['distinct'] - 1) / span if span > 0 else 0.0
        lines.append('%s %s %.2f Hz by header stamps (set %g, %+.2f %%), %d of %d stamps, %d '
                     'duplicates' % (p, topic, rate, hz, 100.0 * (rate / hz - 1.0) if hz else 0,
                                     s['distinct'], expected, s['received'] - s['distinct']))
    for w in m['warn'][:4]:
        lines.append('%s launch said: %s' % (p, w.strip()[:200]))
    return lines


def measure_in_child(name, seconds, warmup, tmp, paced=False, bare_lib='', bare_steps=0):
    """measure_launch in a process of its own (rospy joins one master per process)."""
    path = os.path.join(tmp, '%s.json' % name)
    subprocess.run(['/usr/bin/python3', os.path.abspath(__file__), name, str(seconds),
                    str(warmup), tmp, path, 'paced' if paced else 'fast', bare_lib or '',
                    str(bare_steps)], check=True, timeout=seconds + warmup + 900)
    m = json.load(open(path))
    m['procs'] = {int(k): tuple(v) for k, v in m['procs'].items()}
    m['threads'] = {int(k): tuple(v) for k, v in m['threads'].items()}
    return m


def run(names, seconds, warmup, bare_steps, build_bare_c, bare_c_loop, paced=False):
    tmp = tempfile.mkdtemp(prefix='sim_rtf_launch_')
    lib = build_bare_c(tmp)
    out = []
    for name in names:
        if name not in LAUNCHES:
            raise SystemExit('sim_rtf --launch: unknown launch %r (known: %s)'
                             % (name, ', '.join(LAUNCHES)))
        m = measure_in_child(name, seconds, warmup, tmp, paced, lib, bare_steps)
        if paced:       # the figure is the achieved rate and the CPU per simulated second
            bare = bare_cpu = float('nan')
        else:
            # the runs interleaved with ours: total simulated over total wall / CPU time
            steps = [1.0 / len(m['bare_runs'])] * len(m['bare_runs'])
            bare = sum(steps) / sum(k / r[0] for k, r in zip(steps, m['bare_runs']))
            bare_cpu = sum(steps) / sum(k / r[1] for k, r in zip(steps, m['bare_runs']))
        lines = report(name, m, bare, bare_cpu)
        for line in lines:
            print(line, flush=True)
        out.append((name, m, bare, bare_cpu))
    return out


def child_main(argv):
    name, seconds, warmup, tmp, out, mode, bare_lib, bare_steps = argv[1:9]
    m = measure_launch(name, float(seconds), float(warmup), tmp, paced=mode == 'paced',
                       bare_lib=bare_lib or None, bare_steps=int(bare_steps))
    with open(out, 'w') as f:
        json.dump(m, f)


if __name__ == '__main__':
    import sys
    child_main(sys.argv)
