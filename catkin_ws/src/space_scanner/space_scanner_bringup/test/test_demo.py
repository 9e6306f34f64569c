"""`make demo` end to end, as a user runs it (`rosrun space_scanner_bringup demo`): the space
scanner explores the office until no frontier is left, the map is saved, the robot restarts on
it with AMCL + move_base and reaches a goal in every room. Slow (~15 min of a quiet 2-core
machine), so in `make test-full` only."""
import json
import os
import subprocess

import pytest


@pytest.mark.full
@pytest.mark.timeout(3600)
def test_demo_maps_the_office_then_reaches_every_goal(tmp_path):
    out = tmp_path / 'demo'
    r = subprocess.run(['rosrun', 'space_scanner_bringup', 'demo', '--out', str(out)],
                       capture_output=True, text=True, timeout=3500,
                       env=dict(os.environ, DISPLAY=''))
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-2000:]
    for name in ('office_map.yaml', 'office_map.pgm', 'office_map_path.png', 'summary.json'):
        assert (out / name).is_file(), name
    s = json.loads((out / 'summary.json').read_text())
    assert s['exploration_finished'], s
    assert s['goals_reached'] == s['goals'] == 5, s
    # every goal of phase 3 runs on the new simulation's clock (phase 1's clock once made the
    # first goal "reached in -347 s" and move_base recalled the others as older than it)
    assert all(0 < t < 120 for t in s['goal_times_sim_s']), s
    assert s['map_walls_found'] >= 0.95 and s['map_false_occupied'] <= 0.02, s
    assert s['slam_ate_rms_m'] <= 0.05 and s['amcl_ate_rms_m'] <= 0.05, s
    assert '=== main demo summary' in r.stdout


def test_demo_prints_the_web_url_with_its_token(tmp_path):
    """`make demo web:=true` prints the URL course_web_server printed, token included (the
    page answers 403 without it)."""
    from space_scanner_bringup.demo import printed_web_url
    log = tmp_path / 'web.log'
    log.write_text('... logging to ...\n\n    course_web: open http://localhost:8080/?token=ab12cd\n\n')
    assert printed_web_url(str(log), 8080, timeout=1.0) == 'http://localhost:8080/?token=ab12cd'
    missing = printed_web_url(str(tmp_path / 'none.log'), 8081, timeout=0.6)
    assert missing.startswith('http://localhost:8081/?token=') and 'log' in missing
