"""Scripted runs of rqt for tests: the real main window and plugins, driven from the GUI thread.

`run(argv, scenario, standalone=None)` starts rqt_gui's Main exactly as the `rqt` script does and
calls `scenario(main, step)` every 100 ms until it returns True; `emit(**kw)` prints one JSON
line ("RQT_STATE {...}") the test reads from the process output. `wait_for_file(path)` lets the
test take an X screenshot before the window closes.
"""
import json
import os
import sys
import time


def emit(**kw):
    print('RQT_STATE ' + json.dumps(kw, sort_keys=True), flush=True)


def widget_rect(widget):
    """Global (screen) rectangle [x, y, w, h] of a widget."""
    p = widget.mapToGlobal(widget.rect().topLeft())
    return [p.x(), p.y(), widget.width(), widget.height()]


def run(argv, scenario, standalone=None, timeout=90.0, plugin_argument_provider=None):
    from rqt_gui.main import Main
    main = Main(filename=argv[0])
    started = time.time()
    state = {'step': 0}

    def tick():
        from python_qt_binding.QtCore import QTimer
        state['step'] += 1
        try:
            done = scenario(main, state['step'])
        except Exception as e:
            import traceback
            traceback.print_exc()
            emit(error='%s: %s' % (type(e).__name__, e))
            done = True
        if not done and time.time() - started > timeout:
            emit(error='scenario timed out after %.0f s' % timeout)
            done = True
        if done:
            main.main_window.close()
        else:
            QTimer.singleShot(100, tick)

    main.on_started.append(lambda m: tick())
    return main.main(argv, standalone=standalone, plugin_argument_provider=plugin_argument_provider)


def file_exists(path):
    return os.path.exists(path)


def running_instance(main, plugin_id):
    """The plugin object of the first running instance of plugin_id (or None)."""
    for (pid, _serial), handler in sorted(main.plugin_manager.running.items()):
        if pid == plugin_id:
            return handler.instance
    return None


# ---- test side ---------------------------------------------------------------------------------
def states(output):
    """Every RQT_STATE dictionary printed so far by a scripted run."""
    out = []
    for line in output.splitlines():
        if line.startswith('RQT_STATE '):
            out.append(json.loads(line[len('RQT_STATE '):]))
    return out


def gui_env(base_env, display, config_dir):
    """Environment for a GUI child: the test's X display, settings in `config_dir`, and no
    QT_QPA_PLATFORM=offscreen (that the test runner sets for in-process Qt)."""
    env = dict(base_env, DISPLAY=display, XDG_CONFIG_HOME=str(config_dir))
    env.pop('QT_QPA_PLATFORM', None)
    return env


def dark_fraction(rgb, rect, level=120):
    """Fraction of pixels darker than `level` in rect [x, y, w, h] of an RGB screenshot."""
    x, y, w, h = [int(v) for v in rect]
    region = rgb[max(0, y):y + h, max(0, x):x + w]
    if region.size == 0:
        return 0.0
    return float((region.max(axis=2) < level).mean())


if __name__ == '__main__':
    sys.exit('import course_testing.rqt_driver from a test script')
