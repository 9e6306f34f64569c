"""ros_mac_authentication run as a user does (rosrun) without ~secret_file_location: the
original's error line and its exit status (MISSING_PARAMETER, -1: 255)."""
from course_testing import RosCore, run


def test_missing_secret_file_location_is_one_line_and_exit_255(tmp_path):
    core = RosCore(log_dir=str(tmp_path / 'ros_log'))
    core.start()
    try:
        log = tmp_path / 'node.log'
        code, timed_out = run(['rosrun', 'rosauth', 'ros_mac_authentication'], 120,
                              env=core.env, log=str(log))
        out = log.read_text(errors='replace')
        assert not timed_out, out
        assert code == 255, out
        assert "Parameter 'secret_file_location' not found." in out
        assert 'Authentication Server Started' not in out
    finally:
        core.stop()
