"""Entry point of turtlesim_node: a Qt window when a display is reachable, headless otherwise."""
import ctypes
import ctypes.util
import os
import signal
import sys
import threading
import time

import rospy

from turtlesim.sim_node import TurtleSimNode


def display_reachable():
    """True when $DISPLAY names an X server we can open (so Qt will not abort)."""
    display = os.environ.get('DISPLAY')
    if not display or os.environ.get('QT_QPA_PLATFORM', '') == 'offscreen':
        return False
    lib = ctypes.util.find_library('X11')
    if not lib:
        return True      # let Qt try
    x11 = ctypes.cdll.LoadLibrary(lib)
    x11.XOpenDisplay.restype = ctypes.c_void_p
    x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
    x11.XCloseDisplay.argtypes = [ctypes.c_void_p]
    deadline = time.monotonic() + 2.0      # an X server that is just starting: retry briefly
    while True:
        handle = x11.XOpenDisplay(display.encode())
        if handle:
            x11.XCloseDisplay(handle)
            return True
        if time.monotonic() > deadline:
            return False
        time.sleep(0.1)


def main(argv=None):
    argv = rospy.myargv(sys.argv if argv is None else argv)
    rospy.init_node('turtlesim', disable_signals=True)
    stop = threading.Event()
    gui = display_reachable()
    if not gui and os.environ.get('DISPLAY') and os.environ.get('QT_QPA_PLATFORM') != 'offscreen':
        rospy.logwarn('cannot open display %s; running headless (no window)', os.environ['DISPLAY'])

    if not gui:
        sim = TurtleSimNode()

        def on_signal(_sig, _frame):
            stop.set()
        signal.signal(signal.SIGINT, on_signal)
        signal.signal(signal.SIGTERM, on_signal)
        sim.run(lambda: stop.is_set() or rospy.is_shutdown())
        rospy.signal_shutdown('turtlesim exiting')
        return 0

    from PyQt5.QtCore import QTimer
    from PyQt5.QtWidgets import QApplication
    from turtlesim.window import TurtleWindow

    app = QApplication(argv[:1])
    sim = TurtleSimNode()
    window = TurtleWindow(sim)
    sim.on_update = window.notify
    window.show()

    def on_signal(_sig, _frame):
        stop.set()
        app.quit()
    signal.signal(signal.SIGINT, on_signal)
    signal.signal(signal.SIGTERM, on_signal)
    # Python runs signal handlers only when it gets control: give it a slot to run in, and
    # close the window when ROS shuts down (e.g. rosnode kill)
    watchdog = QTimer()
    watchdog.timeout.connect(lambda: app.quit() if rospy.is_shutdown() or stop.is_set() else None)
    watchdog.start(100)

    worker = threading.Thread(target=sim.run, name='turtlesim-update',
                              args=(lambda: stop.is_set() or rospy.is_shutdown(),), daemon=True)
    worker.start()
    app.exec_()
    stop.set()
    worker.join(2.0)
    rospy.signal_shutdown('turtlesim window closed')
    return 0
