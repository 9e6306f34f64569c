"""roslaunch's own check of a launch file with name:=value args (as rostest's roslaunch_check:
includes, args, every node's package and executable) and the nodes it would start. It runs in a
separate /usr/bin/python3 because roslaunch reads the args from sys.argv."""
import subprocess

_CHECK = r'''
import sys, roslaunch.rlutil, roslaunch.config
f = sys.argv[1]
sys.argv[1:] = sys.argv[2:]
err = roslaunch.rlutil.check_roslaunch(f)
if err:
    print('ERROR ' + err.replace('\n', ' | '))
    sys.exit(1)
cfg = roslaunch.config.load_config_default([f], 11311, verbose=False)
for n in cfg.nodes:
    print('NODE %s %s %s' % (n.package, n.type, (n.namespace or '/') + n.name))
print('NODES %d' % len(cfg.nodes))
'''


def check_launch(path, args=(), timeout=180):
    """-> (None, [(package, type, name), ...]) when `path` resolves with `args`, else
    (what roslaunch said, [])."""
    r = subprocess.run(['/usr/bin/python3', '-c', _CHECK, path] + list(args), capture_output=True,
                       text=True, timeout=timeout)
    lines = r.stdout.splitlines()
    if r.returncode != 0 or not any(line.startswith('NODES ') for line in lines):
        return '%s %s' % (r.stdout[-1500:], r.stderr[-1500:]), []
    return None, [tuple(line.split()[1:4]) for line in lines if line.startswith('NODE ')]
