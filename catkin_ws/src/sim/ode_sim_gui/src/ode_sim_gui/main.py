"""gzclient: the window on a running simulator (it waits for one; several windows, or none,
may watch one simulator; closing the window leaves the simulator running; when the simulator
exits the window closes with one line). Without a display: one line, exit 0."""
import os
import signal
import sys

NO_DISPLAY = ('gzclient: no display (DISPLAY is not set), the window cannot open; the '
              'simulator runs on without it')


WINDOW_NICE = 10


def yield_cpu():
    """The window runs at a lower CPU priority than the simulator (nice +10): on a machine with
    few cores and software OpenGL (llvmpipe renders on every core) the view then takes the time
    the simulation leaves, instead of slowing it."""
    try:
        os.nice(WINDOW_NICE)
    except OSError:
        pass


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if not os.environ.get('DISPLAY'):
        print('[INFO] ' + NO_DISPLAY, flush=True)
        return 0
    import rospy
    from PyQt5 import QtCore, QtWidgets
    from ode_sim_gui.client import SimClient
    from ode_sim_gui.window import MainWindow

    ros_args = [a for a in argv if ':=' in a]
    qt_args = [a for a in argv if ':=' not in a and a not in ('--verbose', '-g')]
    app = QtWidgets.QApplication([sys.argv[0]] + qt_args)
    app.setApplicationName('Gazebo')
    yield_cpu()
    rospy.init_node('gzclient', argv=[sys.argv[0]] + ros_args, anonymous=True,
                    disable_signals=True)
    win = MainWindow(SimClient('/gazebo'))
    win.show()
    signal.signal(signal.SIGINT, lambda *_: app.quit())
    signal.signal(signal.SIGTERM, lambda *_: app.quit())
    keepalive = QtCore.QTimer()          # lets Python run signal handlers
    keepalive.timeout.connect(lambda: None)
    keepalive.start(200)
    rc = app.exec_()
    rospy.signal_shutdown('window closed')
    return rc
