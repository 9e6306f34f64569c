"""map_server / map_saver executables without a master: a bad map YAML gives the original's one
line on stderr and exit status 255 (no traceback); map_saver -h prints the usage."""
import os
import subprocess

SCRIPTS = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), 'scripts')


def run(*args):
    env = dict(os.environ, ROS_MASTER_URI='http://localhost:1')     # no master: must not be needed
    return subprocess.run(['/usr/bin/python3', os.path.join(SCRIPTS, args[0])] + list(args[1:]), env=env,
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True, timeout=60)


def test_bad_yaml_one_line_and_exit_255(tmp_path):
    (tmp_path / 'm.yaml').write_text('image: m.pgm\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\n'
                                     'free_thresh: 0.196\n')
    res = run('map_server', str(tmp_path / 'm.yaml'))
    assert res.returncode == 255
    lines = res.stderr.strip().splitlines()
    assert len(lines) == 1 and 'The map does not contain a resolution tag or it is invalid.' in lines[0]
    assert 'Traceback' not in res.stderr


def test_missing_image(tmp_path):
    (tmp_path / 'm.yaml').write_text('image: none.png\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\n'
                                     'occupied_thresh: 0.65\nfree_thresh: 0.196\n')
    res = run('map_server', str(tmp_path / 'm.yaml'))
    assert res.returncode == 255 and 'failed to open image file' in res.stderr and 'Traceback' not in res.stderr


def test_usage():
    res = run('map_server')
    assert res.returncode == 255 and 'USAGE: map_server <map.yaml>' in res.stderr
    res = run('map_saver', '-h')
    assert res.returncode == 0 and 'map_saver [--occ <threshold_occupied>]' in res.stdout
