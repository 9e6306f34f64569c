"""gzclient: the simulator's window (ode_sim_gui, title "Gazebo"): a 3D view drawn by ode_sim's
own renderer, the world tree, Insert, move, delete, pause/step and Save World As, on the
/gazebo/* API of a running simulator. Without a display it says so in one line and exits 0, so
`gui:=true` launches also run headless."""
import sys

from ode_sim_gui.main import NO_DISPLAY, main as _window_main   # noqa: F401 (NO_DISPLAY)


def main(argv=None):
    return _window_main(sys.argv[1:] if argv is None else argv)
