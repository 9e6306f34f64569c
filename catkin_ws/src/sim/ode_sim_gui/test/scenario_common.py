"""What the two scripted scenarios (student_scenario.py, editor_scenario.py) share besides the
`ros` fixture (conftest.py): the simulator's window opened on /gazebo, and waiting on the Qt
event loop for a condition."""
import time

from ode_sim_gui.client import SimClient
from ode_sim_gui.window import MainWindow


def open_window(qtbot, model, what, size=(1400, 900)):
    """The window (gzclient's MainWindow) on /gazebo, shown at `size`, once `model` is in its
    scene (`what` names it in the timeout's message)."""
    win = MainWindow(SimClient('/gazebo'))
    qtbot.addWidget(win)
    win.resize(*size)
    win.show()
    qtbot.waitExposed(win)
    wait_until(qtbot, lambda: model in win.scene.model_names(), 120, what)
    return win


def wait_until(qtbot, predicate, timeout=60.0, what='condition'):
    """Process Qt events until predicate() holds; AssertionError naming `what` after `timeout`
    wall seconds (a hang guard, not a speed threshold)."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if predicate():
            return
        qtbot.wait(100)
    raise AssertionError('timed out waiting for %s' % what)
