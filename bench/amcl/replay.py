#!/usr/bin/env python3
"""Replays a recorded drive (rosbag: /scan, /tf, /gazebo/model_states) through amcl's core
(amcl.localizer, the node's update logic without messaging) as fast as possible, starting
0.5 m / 20 deg off the true pose. Prints convergence time, tracking RMS against the ground
truth and the cost per filter update.

    replay.py BAG MAP_YAML [--param value ...]   (Config fields, e.g. --update_min_d 0.05)"""
import math
import os
import sys
import time

import numpy as np
import rosbag
import yaml

from amcl import convert
from amcl.localizer import Config, Localizer
from amcl.sensors import angle_diff

BASE, ODOM, MODEL = 'base_footprint', 'odom', 'robot'
CONV_XY, CONV_YAW = 0.05, 0.05
HOLD_S = 0.5              # s the error must stay within tolerance to count as converged


def load_map(path):
    import importlib.util
    here = os.path.dirname(os.path.abspath(__file__))
    spec = importlib.util.spec_from_file_location(
        'check_amcl_sim', os.path.join(here, '..', '..', 'catkin_ws', 'src', 'navigation', 'amcl', 'test',
                                       'check_amcl_sim.py'))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return convert.map_from_msg(mod.load_map(path))


def interp(times, poses, t):
    k = int(np.searchsorted(times, t))
    if k <= 0 or k >= len(times):
        return None
    a = (t - times[k - 1]) / max(times[k] - times[k - 1], 1e-9)
    p0, p1 = poses[k - 1], poses[k]
    return np.array([p0[0] + a * (p1[0] - p0[0]), p0[1] + a * (p1[1] - p0[1]),
                     p0[2] + a * float(angle_diff(p1[2], p0[2]))])


def read(bag_path):
    odom_t, odom_p, gt_t, gt_p, scans, laser = [], [], [], [], [], {}
    chain = {}
    with rosbag.Bag(bag_path) as bag:
        for topic, msg, t in bag.read_messages(topics=['/scan', '/tf', '/tf_static', '/gazebo/model_states']):
            if topic in ('/tf', '/tf_static'):
                for tr in msg.transforms:
                    if tr.header.frame_id == ODOM and tr.child_frame_id == BASE:
                        odom_t.append(tr.header.stamp.to_sec())
                        odom_p.append(convert.pose_from_transform(tr))
                    elif tr.child_frame_id not in chain:
                        chain[tr.child_frame_id] = tr
            elif topic == '/scan':
                scans.append(msg)
            else:
                if MODEL in msg.name:
                    p = msg.pose[msg.name.index(MODEL)]
                    gt_t.append(t.to_sec())
                    gt_p.append(np.array([p.position.x, p.position.y, convert.yaw_of(p.orientation)]))
    # the laser in the base frame: compose the chain laser -> ... -> base_footprint (planar)
    frame, pose = scans[0].header.frame_id, np.zeros(3)
    while frame != BASE:
        tr = chain[frame]
        from amcl.localizer import compose
        pose = compose(convert.pose_from_transform(tr), pose)
        frame = tr.header.frame_id
    laser = chain[scans[0].header.frame_id]
    laser.transform.translation.x, laser.transform.translation.y = pose[0], pose[1]
    return (np.array(odom_t), np.array(odom_p), np.array(gt_t), np.array(gt_p), scans, laser)


def run(bag_path, map_path, overrides, seed=1, quiet=False, t_end=None, truth_odom=False):
    odom_t, odom_p, gt_t, gt_p, scans, laser = read(bag_path)
    if truth_odom:
        odom_t, odom_p = gt_t, gt_p
    cfg = Config(**overrides)
    gmap = load_map(map_path)
    loc = Localizer(cfg, rng=np.random.default_rng(seed))
    # start when the robot starts to move
    moving = [k for k in range(1, len(gt_p)) if np.hypot(*(gt_p[k, :2] - gt_p[0, :2])) > 0.01 or
              abs(float(angle_diff(gt_p[k, 2], gt_p[0, 2]))) > 0.01]
    t_start = gt_t[moving[0]] - 0.5 if moving else gt_t[0]
    truth0 = interp(gt_t, gt_p, t_start)
    off = np.array([0.5 * math.cos(math.radians(-45)), 0.5 * math.sin(math.radians(-45)), math.radians(20)])
    loc.set_map(gmap, initial_pose=truth0 + off, initial_cov=cfg.initial_cov)
    converged, costs, trace = None, [], []
    for scan in scans:
        ts = scan.header.stamp.to_sec()
        if ts < t_start:
            continue
        if t_end is not None and ts - t_start > t_end:
            break
        op, gt = interp(odom_t, odom_p, ts), interp(gt_t, gt_p, ts)
        if op is None or gt is None:
            continue
        data = convert.laser_data(scan, laser)
        c0 = time.process_time()
        res = loc.process(op, data)
        cost = time.process_time() - c0
        if res.updated:
            costs.append(cost)
        est = res.map_to_odom
        if est is None:
            continue
        from amcl.localizer import compose
        pose = compose(est, op)
        e = (float(np.hypot(*(pose[:2] - gt[:2]))), abs(float(angle_diff(pose[2], gt[2]))))
        trace.append((ts - t_start, e[0], e[1], res.stats.get('particles', 0) if res.updated else -1))
    period = float(np.median(np.diff([s.header.stamp.to_sec() for s in scans])))
    # converged: the first scan from which the error stays within CONV_XY / CONV_YAW for HOLD_S
    tr = np.array([row[:3] for row in trace])
    ok = (tr[:, 1] < CONV_XY) & (tr[:, 2] < CONV_YAW)
    converged = None
    for k in range(len(tr)):
        window = tr[:, 0] <= tr[k, 0] + HOLD_S
        window[:k] = False
        if ok[window].all() and tr[window, 0].max() >= tr[k, 0] + HOLD_S - 0.5:
            converged = float(tr[k, 0])
            break
    after = tr[tr[:, 0] >= converged] if converged is not None else tr[:0]
    cpu = np.array(costs) if costs else np.array([np.nan])
    out = {
        'converge_s': None if converged is None else round(converged, 2),
        'rms_xy': round(float(np.sqrt(np.mean(after[:, 1] ** 2))), 4) if len(after) else None,
        'rms_yaw': round(float(np.sqrt(np.mean(after[:, 2] ** 2))), 4) if len(after) else None,
        'max_xy': round(float(after[:, 1].max()), 4) if len(after) else None,
        'max_yaw': round(float(after[:, 2].max()), 4) if len(after) else None,
        'outside_tolerance': round(float(np.mean(~ok[tr[:, 0] >= converged])), 4) if len(after) else None,
        'cpu_ms_per_update': round(1000 * float(np.mean(cpu)), 2),
        'cpu_ms_max': round(1000 * float(np.max(cpu)), 2),
        'scan_period_s': round(period, 4),
        'cpu_per_scan_period': round(float(np.mean(cpu)) / period, 4),
        'updates': len(costs),
        'drive_s': round(float(min(scans[-1].header.stamp.to_sec() - t_start, t_end or 1e9)), 1),
    }
    if not quiet:
        for row in trace[::3]:
            print('t %6.2f  err %.3f m %.3f rad  particles %d' % row)
    return out


def main(argv):
    overrides = {}
    args = argv[3:]
    t_end = None
    quiet = '--quiet' in args
    if quiet:
        args.remove('--quiet')
    truth_odom = '--truth_odom' in args
    if truth_odom:
        args.remove('--truth_odom')
    if '--t_end' in args:
        k = args.index('--t_end')
        t_end = float(args[k + 1])
        del args[k:k + 2]
    for k in range(0, len(args), 2):
        name = args[k].lstrip('-')
        overrides[name] = type(getattr(Config, name))(args[k + 1])
    out = run(argv[1], argv[2], overrides, t_end=t_end, truth_odom=truth_odom, quiet=quiet)
    print(yaml.safe_dump(out, sort_keys=False))


if __name__ == '__main__':
    main(sys.argv)
