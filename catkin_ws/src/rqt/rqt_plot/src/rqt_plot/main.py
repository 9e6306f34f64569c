"""rqt_plot command line: argument parsing, master check, node start and the Qt event loop."""
import argparse
import os
import signal
import socket
import sys


def _report(line, error=False):
    if error:
        print('rqt_plot: ERROR: %s' % line, file=sys.stderr, flush=True)
    else:
        print('rqt_plot: %s' % line, flush=True)


def _fail(line):
    print('rqt_plot: %s' % line, file=sys.stderr, flush=True)
    return 1


def parse_args(argv):
    parser = argparse.ArgumentParser(
        prog='rqt_plot', description='Plot numeric fields of ROS topics against time.',
        epilog='examples: rqt_plot /turtle1/pose/x /turtle1/pose/y;  rqt_plot /turtle1/pose/x:y:theta;'
               '  rqt_plot /joint_states/velocity[0]')
    parser.add_argument('topics', nargs='*', help='topic/field specs to plot')
    parser.add_argument('-P', '--pause', action='store_true', help='start in paused state')
    parser.add_argument('-e', '--empty', action='store_true',
                        help='accepted for compatibility (no saved topics are restored anyway)')
    parser.add_argument('-w', '--window', type=float, default=10.0,
                        help='width of the scrolling time window in seconds (default 10)')
    args = parser.parse_args(argv)
    if args.window <= 0:
        parser.error('--window must be > 0 (got %s)' % args.window)
    return args


def main(argv=None):
    import rospy
    from rqt_plot.rosplot import PlotFieldError, expand_specs, parse_field_path, resolve_spec

    argv = rospy.myargv(sys.argv if argv is None else argv)[1:]
    args = parse_args(argv)
    try:
        import rosgraph.names
        specs = [rosgraph.names.script_resolve_name('rqt_plot', s) for s in expand_specs(args.topics)]
        for spec in specs:
            parse_field_path(spec)           # syntax only: topic and fields are checked later
    except PlotFieldError as e:
        return _fail(str(e))

    import rosgraph
    master = rosgraph.Master('/rqt_plot')
    socket.setdefaulttimeout(3.0)
    try:
        master.getPid()
    except Exception:
        return _fail('cannot reach the ROS master at %s (is roscore running?)' % master.master_uri)
    finally:
        socket.setdefaulttimeout(None)

    rospy.init_node('rqt_plot', anonymous=True, disable_signals=True)

    def topics():
        return dict(rospy.get_published_topics())

    # fields of topics that are published already are checked before any window opens
    good = []
    published = topics()
    for spec in specs:
        try:
            resolve_spec(spec, published)
            good.append(spec)
        except PlotFieldError as e:
            _report(str(e), error=True)
    if specs and not good:
        rospy.signal_shutdown('nothing to plot')
        return _fail('none of the requested fields can be plotted')

    from PyQt5 import QtCore, QtWidgets
    from rqt_plot.plot_widget import PlotWidget, PlotWindow

    app = QtWidgets.QApplication([sys.argv[0]])
    start_time = rospy.get_time()
    widget = PlotWidget(topics, start_time, window=args.window, report=_report, paused=args.pause)
    widget.add_specs(good)
    window = PlotWindow(widget)
    window.show()

    status = {'code': 0}

    def check():
        if rospy.is_shutdown():
            app.quit()
        elif widget.nothing_plottable():
            _fail('none of the requested fields can be plotted')
            status['code'] = 1
            app.quit()

    # let Python run its signal handlers (Ctrl-C) while Qt's loop runs
    signal.signal(signal.SIGINT, lambda *_: app.quit())
    signal.signal(signal.SIGTERM, lambda *_: app.quit())
    timer = QtCore.QTimer()
    timer.timeout.connect(check)
    timer.start(200)
    app.exec_()
    timer.stop()
    widget.shutdown()
    rospy.signal_shutdown('rqt_plot closed')
    _exit_without_teardown(status['code'])


def _exit_without_teardown(code):
    """Leave once the window is closed and the node shut down, without Python's teardown of the
    Qt objects: PyQt + pyqtgraph can crash there (SIGSEGV after a clean close, seen under load);
    pyqtgraph's own remedy (pyqtgraph.exit) does the same. Output and ROS logs are flushed first."""
    import logging
    sys.stdout.flush()
    sys.stderr.flush()
    logging.shutdown()
    os._exit(code)
