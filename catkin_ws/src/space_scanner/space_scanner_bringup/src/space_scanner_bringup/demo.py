"""The project's main demo (make demo): the space scanner maps the office on its own, then
navigates on the map it made.

1. explore.launch sim:=true — gmapping + move_base + explore_lite's frontier exploration —
   until no frontier is left (or the simulated-time budget ends); ground truth and the SLAM
   pose are recorded all along.
2. `rosrun map_server map_saver -f OUT/office_map` saves the map; OUT/office_map_path.png shows
   the driven trajectory over it.
3. navigation.launch sim:=true map_file:=OUT/office_map.yaml — AMCL + move_base — takes the
   robot to a set of goals in every room.
4. A summary table: map quality against the office's ground-truth map, ATE of SLAM and AMCL,
   goals reached and their times (all simulated time).
Headless unless DISPLAY is set (then RViz shows each phase); with --web (make demo web:=true) the
course web view (course_web) shows the robot, scans, map and plans in a browser."""
import argparse
import json
import os
import signal
import subprocess
import sys
import threading
import time

import numpy as np

import course_runtime
from course_runtime import Proc, RosCore
from space_scanner_bringup import metrics, pace

GOALS = [   # (x, y) in the office: middle room, the corridor, left room, right room, back home
    (1.0, -1.0), (0.0, 3.0), (-3.5, -2.5), (3.5, -2.5), (0.0, 0.0)]


class Recorder:
    """Ground truth (the simulator's model state of `robot`) and the estimated pose (TF
    map -> base_footprint), both stamped with simulated time, sampled every TRUTH_PERIOD
    simulated seconds by one polling thread. The truth comes from /gazebo/get_model_state
    (its header carries the simulated time of the pose), not from /gazebo/model_states: that
    topic is published every physics step while anyone subscribes (as Gazebo does), a thousand
    messages of every model per simulated second that the simulator would build and this
    process decode only to keep ten of them."""

    TRUTH_PERIOD = 0.1      # simulated s between ground-truth samples
    TF_PERIOD = 0.2         # simulated s between estimate samples

    def __init__(self):
        import rospy
        import tf2_ros
        from gazebo_msgs.srv import GetModelState
        self.rospy = rospy
        self.lock = threading.Lock()
        self.truth, self.estimate = [], []
        self.buf = tf2_ros.Buffer()
        self.listener = tf2_ros.TransformListener(self.buf)
        rospy.wait_for_service('/gazebo/get_model_state', timeout=120)
        self.get_state = rospy.ServiceProxy('/gazebo/get_model_state', GetModelState,
                                            persistent=True)
        self.running = True
        self.thread = threading.Thread(target=self.poll, daemon=True)
        self.thread.start()

    def sample_truth(self):
        try:
            res = self.get_state('robot', '')
        except Exception:   # the simulator is going away: keep what we have
            return
        if not res.success:
            return
        t = res.header.stamp.to_sec()
        with self.lock:
            if not self.truth or t - self.truth[-1][0] >= self.TRUTH_PERIOD - 1e-6:
                self.truth.append((t, res.pose.position.x, res.pose.position.y))

    def sample_estimate(self):
        import rospy
        try:
            tr = self.buf.lookup_transform('map', 'base_footprint', rospy.Time(0))
        except Exception:   # no map yet: keep polling
            return
        t = tr.header.stamp.to_sec()
        with self.lock:
            if not self.estimate or t - self.estimate[-1][0] >= self.TF_PERIOD - 1e-6:
                self.estimate.append((t, tr.transform.translation.x, tr.transform.translation.y))

    def poll(self):
        import rospy
        while self.running and not rospy.is_shutdown():
            self.sample_truth()
            self.sample_estimate()
            time.sleep(0.05)     # wall seconds: every 0.1 s simulated at up to 2x real time

    def stop(self):
        self.running = False
        self.thread.join(timeout=5.0)
        try:
            self.get_state.close()
        except Exception:
            pass

    def take(self):
        with self.lock:
            out = list(self.truth), list(self.estimate)
            self.truth, self.estimate = [], []
        return out


def wait_for(cond, timeout, what):
    end = time.monotonic() + timeout
    while not cond():
        if time.monotonic() > end:
            raise RuntimeError('timed out after %.0f s waiting for %s' % (timeout, what))
        time.sleep(0.5)


def sim_now():
    import rospy
    return rospy.get_time()


def explore(out, env, display, sim_budget, say):
    """Phase 1: returns (sim seconds, finished, truth, estimate, map base, pace figures)."""
    log = os.path.join(out, 'explore.log')
    args = ['roslaunch', 'space_scanner_bringup', 'explore.launch', 'sim:=true',
            'rviz:=%s' % ('true' if display else 'false')]
    launch = Proc(args, env=env, log=log)
    try:
        wait_for(lambda: sim_now() > 0, 300, 'the simulation clock (see %s)' % log)
        rec = Recorder()
        meter = pace.PhaseMeter(sim_now)
        mark = meter.start(launch.pid)
        t0 = sim_now()
        say('exploring the office (simulated-time budget %.0f s)' % sim_budget)
        finished = False
        last_report = t0
        while sim_now() - t0 < sim_budget:
            text = launch.output()
            if 'All frontiers traversed/tried out' in text:
                finished = True
                break
            if not launch.alive():
                raise RuntimeError('explore.launch stopped (see %s)' % log)
            if sim_now() - last_report > 60:
                last_report = sim_now()
                f = meter.figures(mark)
                mark = f['point']
                say('  %.0f s of simulated time explored; the last %.0f s at %.2fx real time, '
                    '%.2f CPU s per simulated s' % (last_report - t0, f['sim_s'], f['rtf'],
                                                    f['cpu_per_sim_s']))
            time.sleep(1.0)
        elapsed = sim_now() - t0
        figures = meter.figures()
        say(pace.describe('exploration', figures))
        rec.stop()
        truth, estimate = rec.take()
        base = os.path.join(out, 'office_map')
        r = subprocess.run(['rosrun', 'map_server', 'map_saver', '-f', base], env=env,
                           capture_output=True, text=True, timeout=120)
        if r.returncode != 0:
            raise RuntimeError('map_saver failed: %s' % (r.stdout + r.stderr)[-500:])
        return elapsed, finished, truth, estimate, base, figures
    finally:
        launch.stop()


def navigate(out, env, display, map_yaml, goal_budget, say):
    """Phase 3: returns ([(goal, state, sim seconds, path length, rtf)], truth, estimate, pace
    figures)."""
    import actionlib
    import rospy
    from move_base_msgs.msg import MoveBaseAction, MoveBaseGoal
    log = os.path.join(out, 'navigation.log')
    args = ['roslaunch', 'space_scanner_bringup', 'navigation.launch', 'sim:=true',
            'map_file:=%s' % map_yaml, 'rviz:=%s' % ('true' if display else 'false')]
    # this process still holds phase 1's last /clock: wait for the new simulation's clock,
    # which starts again at 0 (goals stamped with the old time would be older than every
    # later goal, and move_base's simple action server recalls a goal older than its last)
    old_clock = sim_now()
    launch = Proc(args, env=env, log=log)
    results = []
    try:
        wait_for(lambda: 0 < sim_now() < old_clock or (old_clock == 0 and sim_now() > 0), 300,
                 'the simulation clock (see %s)' % log)
        rec = Recorder()
        meter = pace.PhaseMeter(sim_now)
        meter.start(launch.pid)
        client = actionlib.SimpleActionClient('move_base', MoveBaseAction)
        if not client.wait_for_server(rospy.Duration(300)):
            raise RuntimeError('no move_base action server (see %s)' % log)
        for gx, gy in GOALS:
            goal = MoveBaseGoal()
            goal.target_pose.header.frame_id = 'map'
            goal.target_pose.header.stamp = rospy.Time.now()
            goal.target_pose.pose.position.x, goal.target_pose.pose.position.y = gx, gy
            goal.target_pose.pose.orientation.w = 1.0
            t0 = sim_now()
            w0 = time.monotonic()
            with rec.lock:
                start = len(rec.truth)
            client.send_goal(goal)
            while client.get_state() in (0, 1) and sim_now() - t0 < goal_budget:
                if not launch.alive():
                    raise RuntimeError('navigation.launch stopped (see %s)' % log)
                time.sleep(0.5)
            if client.get_state() in (0, 1):
                client.cancel_goal()
            state = client.get_state()
            with rec.lock:
                driven = metrics.path_length(rec.truth[start:])
            took, wall = sim_now() - t0, time.monotonic() - w0
            rtf = took / wall if wall > 0 else 0.0
            results.append(((gx, gy), state, took, driven, rtf))
            say('  goal (%.1f, %.1f): %s in %.0f s, %.1f m driven (%.2fx real time)' % (
                gx, gy, 'reached' if state == 3 else 'NOT reached (state %d)' % state,
                took, driven, rtf))
        figures = meter.figures()
        say(pace.describe('navigation', figures))
        rec.stop()
        truth, estimate = rec.take()
        return results, truth, estimate, figures
    finally:
        launch.stop()


def load_grid(yaml_path):
    from map_server import load_map
    g = load_map(yaml_path)
    return np.asarray(g.data).reshape(g.height, g.width), g.resolution, tuple(g.origin[:2])


def draw_path(map_yaml, truth, png):
    """The saved map with the driven trajectory (ground truth) in red."""
    from PIL import Image, ImageDraw
    cells, res, origin = load_grid(map_yaml)
    h, w = cells.shape
    img = np.full((h, w, 3), 205, dtype=np.uint8)
    img[cells == 0] = 254
    img[cells == 100] = 0
    im = Image.fromarray(img[::-1].copy())
    d = ImageDraw.Draw(im)
    pts = [((x - origin[0]) / res, h - (y - origin[1]) / res) for _t, x, y in truth]
    if len(pts) > 1:
        d.line(pts, fill=(220, 0, 0), width=2)
    im = im.resize((w * 3, h * 3), Image.NEAREST)
    im.save(png)


def printed_web_url(log, port, timeout=60.0):
    """The URL with its token that course_web_server printed in `log` (the page needs the
    token; it is new at each start and only ever printed there)."""
    def url():
        try:
            with open(log, errors='replace') as f:
                for line in f:
                    if 'course_web: open ' in line:
                        return line.split('course_web: open ', 1)[1].strip()
        except OSError:
            return None

    try:
        return course_runtime.wait_for(url, timeout, interval=0.5, what='the web URL')
    except TimeoutError:
        return 'http://localhost:%d/?token=... (printed in the log once course_web starts)' % port


def report(out, wall_s, elapsed, finished, truth1, quality, slam_ate, amcl_ate, results, pace1,
           pace2):
    """Writes OUT/summary.json and prints the demo's summary table; the number of goals reached."""
    reached = sum(1 for r in results if r[1] == 3)
    summary = {
        'exploration_sim_s': round(elapsed, 1), 'exploration_finished': finished,
        'explored_path_m': round(metrics.path_length(truth1), 2),
        'map_walls_found': round(quality['walls_found'], 3),
        'map_false_occupied': round(quality['false_occupied'], 3),
        'map_known_area_m2': round(quality['known_area'], 1),
        'slam_ate_rms_m': round(slam_ate[0], 3), 'slam_ate_max_m': round(slam_ate[1], 3),
        'amcl_ate_rms_m': round(amcl_ate[0], 3), 'amcl_ate_max_m': round(amcl_ate[1], 3),
        'goals_reached': reached, 'goals': len(results),
        'goal_times_sim_s': [round(r[2], 1) for r in results],
        'wall_s': round(wall_s, 1),
        # achieved real-time factor and the stack's CPU seconds per simulated second
        'exploration_rtf': round(pace1['rtf'], 3),
        'exploration_cpu_per_sim_s': round(pace1['cpu_per_sim_s'], 3),
        'navigation_rtf': round(pace2['rtf'], 3),
        'navigation_cpu_per_sim_s': round(pace2['cpu_per_sim_s'], 3),
        'goal_rtf': [round(r[4], 3) for r in results],
    }
    with open(os.path.join(out, 'summary.json'), 'w') as f:
        json.dump(summary, f, indent=1)
    rows = [
        ('exploration', '%.0f s sim, %.1f m driven, %s' % (
            elapsed, summary['explored_path_m'], 'all frontiers done' if finished else 'budget ended')),
        ('map: walls found', '%.1f %% of the wall cells the robot saw (within one cell)'
         % (100 * quality['walls_found'])),
        ('map: false occupied', '%.1f %% of the occupied cells' % (100 * quality['false_occupied'])),
        ('map: known floor', '%.1f m²' % quality['known_area']),
        ('SLAM ATE', 'RMS %.3f m, max %.3f m' % slam_ate),
        ('AMCL ATE', 'RMS %.3f m, max %.3f m' % amcl_ate),
        ('goals reached', '%d of %d; times %s s sim' % (reached, len(results), summary['goal_times_sim_s'])),
        ('wall time', '%.0f s' % summary['wall_s']),
        ('real-time factor', 'exploration %.2fx, navigation %.2fx (simulated s per wall s)'
         % (pace1['rtf'], pace2['rtf'])),
        ('stack CPU', 'exploration %.2f, navigation %.2f CPU s per simulated s (of 2 cores)'
         % (pace1['cpu_per_sim_s'], pace2['cpu_per_sim_s'])),
    ]
    print('\n=== main demo summary (%s)' % out)
    for k, v in rows:
        print('%-22s %s' % (k, v))
    return reached


def main(argv=None):
    ap = argparse.ArgumentParser(description='The space scanner maps the office, then navigates on its map.')
    ap.add_argument('--out', default='build/demo', help='output folder (default build/demo)')
    ap.add_argument('--explore-time', type=float, default=900.0,
                    help='simulated-time budget of the exploration, s (default 900)')
    ap.add_argument('--goal-time', type=float, default=120.0,
                    help='simulated-time budget of each navigation goal, s (default 120)')
    ap.add_argument('--web', action='store_true',
                    help='also serve the course web view (course_web web.launch: the robot, scans, '
                         'map, plans in a browser at http://localhost:PORT)')
    ap.add_argument('--web-port', type=int, default=8080, help='port of the web view (default 8080)')
    args = ap.parse_args(argv)
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    display = os.environ.get('DISPLAY')

    def say(text):
        print('[demo] ' + text, flush=True)

    def interrupted(signum, _frame):
        raise KeyboardInterrupt('signal %d' % signum)

    # Ctrl-C, and SIGTERM or SIGINT also when started in the background (where a shell ignores
    # SIGINT): the finally blocks stop the launch files and the master
    signal.signal(signal.SIGINT, interrupted)
    signal.signal(signal.SIGTERM, interrupted)

    web = None
    core = RosCore(log_dir=os.path.join(out, 'ros_log'))
    core.start()
    env = dict(os.environ, **core.env)
    os.environ.update(core.env)
    # tf2's C++ core prints TF_REPEATED_DATA and similar warnings of this process's listener
    # straight to fd 2; they go to a log of their own so the console keeps the demo's story
    err_log = os.path.join(out, 'demo_stderr.log')
    err_fd = os.open(err_log, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
    os.dup2(err_fd, 2)
    os.close(err_fd)
    say('logs in %s (demo_stderr.log, explore.log, navigation.log)' % out)
    try:
        import rospy
        rospy.set_param('/use_sim_time', True)
        rospy.init_node('demo', anonymous=True, disable_signals=True)
        if args.web:    # on the demo's master for both phases
            web_log = os.path.join(out, 'web.log')
            web = Proc(['roslaunch', 'course_web', 'web.launch', 'port:=%d' % args.web_port],
                       env=env, log=web_log)
            say('web view: %s (log %s)' % (printed_web_url(web_log, args.web_port), web_log))
        t_wall = time.monotonic()
        elapsed, finished, truth1, est1, base, pace1 = explore(out, env, display,
                                                               args.explore_time, say)
        say('exploration %s after %.0f s of simulated time; map saved to %s.yaml/.pgm' % (
            'finished' if finished else 'stopped at its budget', elapsed, base))
        draw_path(base + '.yaml', truth1, base + '_path.png')
        say('trajectory over the map: %s_path.png' % base)
        import rospkg
        truth_map = os.path.join(rospkg.RosPack().get_path('space_scanner_simulation'), 'maps', 'office.yaml')
        quality = metrics.map_quality(load_grid(base + '.yaml'), load_grid(truth_map))
        slam_ate = metrics.ate(est1, truth1) if est1 else (float('nan'), float('nan'))
        rospy.set_param('/use_sim_time', True)
        results, truth2, est2, pace2 = navigate(out, env, display, base + '.yaml',
                                                args.goal_time, say)
        amcl_ate = metrics.ate(est2, truth2) if est2 else (float('nan'), float('nan'))
        reached = report(out, time.monotonic() - t_wall, elapsed, finished, truth1, quality,
                         slam_ate, amcl_ate, results, pace1, pace2)
        return 0 if finished and reached == len(results) else 1
    except (RuntimeError, OSError) as e:
        say('FAILED: %s' % e)
        return 1
    except KeyboardInterrupt:
        say('interrupted: stopping the simulation and the master')
        return 130
    finally:
        if web is not None:
            web.stop()
        core.stop()


if __name__ == '__main__':
    sys.exit(main())
