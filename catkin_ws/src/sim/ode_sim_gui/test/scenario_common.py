"""What the two scripted scenarios (student_scenario.py, editor_scenario.py) share besides the
`ros` fixture (conftest.py): waiting on the Qt event loop for a condition."""
import time


def wait_until(qtbot, predicate, timeout=60.0, what='condition'):
    """Process Qt events until predicate() holds; AssertionError naming `what` after `timeout`
    wall seconds (a hang guard, not a speed threshold)."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if predicate():
            return
        qtbot.wait(100)
    raise AssertionError('timed out waiting for %s' % what)
