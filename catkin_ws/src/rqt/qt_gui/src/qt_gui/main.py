"""qt_gui main: command line, application, main window, plugin manager and perspectives."""
import argparse
import os
import signal
import sys

from qt_gui.plugin_descriptor import match_plugins
from qt_gui import perspective_file


class OptionError(Exception):
    pass


def hidden_name(plugin_id):
    return '@' + plugin_id.replace('/', '__')


class Main(object):

    def __init__(self, qtgui_path=None, invoked_filename=None, settings_filename='qt_gui'):
        self._qtgui_path = qtgui_path
        self._invoked_filename = invoked_filename
        self._settings_filename = settings_filename
        self.app = None
        self.main_window = None
        self.plugin_manager = None
        self.qsettings = None
        self.perspective = None
        self.on_started = []      # callables(main) run once the window is up (tests, embedding)

    # ---- command line -------------------------------------------------------------------
    def _add_arguments(self, parser, standalone=False, plugin_argument_provider=None):
        common = parser.add_argument_group('Options for GUI instance')
        common.add_argument('-b', '--qt-binding', dest='qt_binding', type=str, metavar='BINDING',
                            help='choose Qt bindings to be used [pyqt|pyside]')
        common.add_argument('--clear-config', dest='clear_config', action='store_true',
                            help='clear the configuration (including all perspectives and plugin settings)')
        if not standalone:
            common.add_argument('-f', '--freeze-layout', dest='freeze_layout', action='store_true',
                                help='freeze the layout of the GUI (prevent rearranging widgets, '
                                     'disable undock/redock)')
        common.add_argument('--force-discover', dest='force_discover', action='store_true',
                            help='force a rediscover of plugins')
        common.add_argument('-h', '--help', action='help', help='show this help message and exit')
        common.add_argument('-ht', '--hide-title', dest='hide_title', action='store_true',
                            help='hide the title label, the icon, and the help button '
                                 '(combine with -l and -f to eliminate the entire title bar)')
        if not standalone:
            common.add_argument('-l', '--lock-perspective', dest='lock_perspective', action='store_true',
                                help='lock the GUI to the used perspective (hide menu bar and close '
                                     'buttons of plugins)')
            common.add_argument('-p', '--perspective', dest='perspective', type=str, metavar='PERSPECTIVE',
                                help='start with this named perspective')
            common.add_argument('--perspective-file', dest='perspective_file', type=str,
                                metavar='PERSPECTIVE_FILE', help='start with a perspective loaded from a file')
        common.add_argument('--reload-import', dest='reload_import', action='store_true',
                            help='reload every imported module')
        if not standalone:
            common.add_argument('-s', '--standalone', dest='standalone_plugin', type=str, metavar='PLUGIN',
                                help='start only this plugin (implies -l). To pass arguments to the '
                                     'plugin use --args')
        common.add_argument('-t', '--on-top', dest='on_top', action='store_true',
                            help='set window mode to always on top')
        common.add_argument('-v', '--verbose', dest='verbose', action='store_true',
                            help='output qDebug messages')
        if not standalone:
            common.add_argument('--args', dest='plugin_args', nargs='*', type=str,
                                help='arbitrary arguments which are passes to the plugin '
                                     '(only with -s, --command-start-plugin or --embed-plugin). '
                                     'It must be the last option since it collects all following options.')
            info = parser.add_argument_group(
                'Options to query information without starting a GUI instance',
                'These options can be used to query information about valid arguments for various options.')
            info.add_argument('--list-perspectives', dest='list_perspectives', action='store_true',
                              help='list available perspectives')
            info.add_argument('--list-plugins', dest='list_plugins', action='store_true',
                              help='list available plugins')
        if plugin_argument_provider:
            plugin_argument_provider(parser)

    def create_providers(self):
        """The plugin providers (rqt_gui adds the ROS ones)."""
        return []

    def prepare(self, args):
        """Hook run before discovery (rqt_gui: nothing needed)."""

    # ---- main ---------------------------------------------------------------------------
    def main(self, argv=None, standalone=None, plugin_argument_provider=None,
             plugin_manager_settings_prefix=''):
        argv = list(sys.argv if argv is None else argv)
        prog = os.path.basename(argv[0] if argv else (self._invoked_filename or 'rqt'))
        args = self._parse_command_line(prog, argv[1:], standalone, plugin_argument_provider)
        if not isinstance(args, argparse.Namespace):
            return args
        self.args = args

        if args.list_perspectives:
            self._open_settings()
            for name in self.perspective_names():
                print(name)
            return 0

        providers = self.create_providers()
        for p in providers:
            if hasattr(p, 'reload_import'):
                p.reload_import = args.reload_import

        if args.list_plugins:
            self._list_plugins(providers)
            return 0

        self._build_window(args, argv[0] if argv else prog, providers)
        found, standalone_id = self._find_standalone(args)
        if not found:
            return 1
        if not args.lock_perspective:
            self.main_window.build_menus(self)
        else:
            self.main_window.menuBar().hide()
        if not self._open_plugins(args, standalone_id):
            return 1
        self._restore_window(standalone=bool(standalone_id))
        self.main_window.closing.connect(self._save_on_close)
        self.main_window.show()
        self._exec()
        return 0

    def _parse_command_line(self, prog, args_list, standalone, plugin_argument_provider):
        """The parsed options (argparse.Namespace, plugin_args set), or the exit code after a
        usage error (printed)."""
        parser = argparse.ArgumentParser(prog=prog, add_help=False)
        help_wanted = '-h' in args_list or '--help' in args_list
        # the plugin's own arguments are shown in the help; otherwise they are left unparsed and
        # handed to the plugin (context.argv())
        self._add_arguments(parser, standalone=bool(standalone),
                            plugin_argument_provider=plugin_argument_provider if help_wanted else None)
        if standalone:
            args, plugin_args = parser.parse_known_args(args_list)
            args.standalone_plugin = standalone
            args.freeze_layout = False
            args.lock_perspective = True
            args.perspective = None
            args.perspective_file = None
            args.list_plugins = args.list_perspectives = False
            args.plugin_args = plugin_args
            return args
        if '--args' in args_list:
            i = args_list.index('--args')
            args = parser.parse_args(args_list[:i])
            args.plugin_args = args_list[i + 1:]
            if not args.standalone_plugin:
                print('Option --args can only be used together with either --standalone, '
                      '--command-start-plugin or --embed-plugin option')
                return 1
        else:
            args = parser.parse_args(args_list)
            args.plugin_args = args.plugin_args or []
        try:
            self._validate(args)
        except OptionError as e:
            print(str(e))
            return 1
        if args.standalone_plugin:
            args.lock_perspective = True
        return args

    @staticmethod
    def _list_plugins(providers):
        descriptors = []
        for p in providers:
            descriptors.extend(p.discover())
            for line in p.errors:
                print(line, file=sys.stderr)
        for name in sorted({d['full_name'] for d in descriptors}):
            print(name)

    def _build_window(self, args, app_name, providers):
        """The application, the main window and the plugin manager (plugins discovered)."""
        from python_qt_binding.QtCore import Qt
        from python_qt_binding.QtGui import QIcon
        from python_qt_binding.QtWidgets import QApplication
        from qt_gui.main_window import MainWindow
        from qt_gui.plugin_manager import PluginManager

        self.app = QApplication.instance() or QApplication([app_name])
        self.app.setAttribute(Qt.AA_DontShowIconsInMenus, False)
        icon = self.application_icon()
        if icon:
            self.app.setWindowIcon(QIcon(icon))
        if not QIcon.themeName():
            QIcon.setThemeName('Tango')
        self._open_settings()
        if args.clear_config:
            self.qsettings.clear()

        self.main_window = MainWindow(title=self.window_title())
        if args.on_top:
            self.main_window.setWindowFlags(self.main_window.windowFlags() | Qt.WindowStaysOnTopHint)
        self.plugin_manager = PluginManager(
            self.main_window, self.qsettings, providers, standalone=bool(args.standalone_plugin),
            lock_perspective=args.lock_perspective, freeze_layout=args.freeze_layout,
            hide_title=args.hide_title)
        self.plugin_manager.message.connect(
            lambda line: self.main_window.statusBar().showMessage(line))
        self.prepare(args)
        self.plugin_manager.discover()

    def _find_standalone(self, args):
        """(True, plugin id of --standalone or None without it), or (False, None) after printing
        why no plugin or several plugins match."""
        if not args.standalone_plugin:
            return True, None
        found = match_plugins(self.plugin_manager.descriptors(), args.standalone_plugin)
        if not found:
            print('qt_gui_main() found no plugin matching "%s"' % args.standalone_plugin)
            print('try passing the option "--force-discover"')
            return False, None
        if len(found) > 1:
            print('qt_gui_main() found multiple plugins matching "%s"' % args.standalone_plugin)
            print('\n'.join(sorted(d['full_name'] for d in found)))
            return False, None
        return True, found[0]['plugin_id']

    def _open_plugins(self, args, standalone_id):
        """Loads the standalone plugin or restores the perspective; False when that failed."""
        if standalone_id:
            self.perspective = hidden_name(standalone_id)
            handler = self.plugin_manager.load_plugin(standalone_id, 0, args.plugin_args,
                                                      perspective=self.perspective)
            if handler is None:
                return False
            if handler.docks:
                self.main_window.setWindowTitle(handler.docks[0].windowTitle())
                handler.docks[0].windowTitleChanged.connect(self.main_window.setWindowTitle)
            return True
        if args.perspective_file:
            name = self.import_perspective(args.perspective_file)
            if name is None:
                return False
            self.perspective = name
        elif args.perspective:
            self.perspective = args.perspective
        else:
            self.perspective = str(self.qsettings.value('current-perspective') or 'Default')
        self._remember_perspective(self.perspective)
        self.plugin_manager.restore_perspective(self.perspective)
        if not args.lock_perspective:
            self.main_window.fill_perspectives_menu()
        return True

    def _exec(self):
        """Qt's event loop until the window closes (SIGINT/SIGTERM close it), then the plugins
        are unloaded and the settings written."""
        from python_qt_binding.QtCore import QTimer
        signal.signal(signal.SIGINT, lambda *_: self.main_window.close())
        signal.signal(signal.SIGTERM, lambda *_: self.main_window.close())
        keepalive = QTimer()
        keepalive.timeout.connect(lambda: None)
        keepalive.start(500)
        for fn in self.on_started:
            QTimer.singleShot(0, lambda fn=fn: fn(self))

        # an exception in a slot must not abort the whole GUI (PyQt5's default): log it
        def excepthook(kind, value, tb):
            import traceback
            print('qt_gui: unhandled exception in a plugin:\n%s' % ''.join(
                traceback.format_exception(kind, value, tb)), file=sys.stderr, flush=True)
        old_hook, sys.excepthook = sys.excepthook, excepthook
        try:
            self.app.exec_()
        finally:
            sys.excepthook = old_hook
        keepalive.stop()
        self.plugin_manager.unload_all()
        self.qsettings.sync()

    def _validate(self, args):
        if args.freeze_layout and not args.lock_perspective:
            raise OptionError('Option --freeze_layout can only be used together with the '
                              '--lock_perspective option')
        if args.list_perspectives and args.list_plugins:
            raise OptionError('Only one --list-* option can be used at a time')
        if args.perspective and args.perspective_file:
            raise OptionError('Only one --perspective-* option can be used at a time')
        if args.perspective_file and not os.path.isfile(args.perspective_file):
            raise OptionError('Option --perspective-file must reference existing file')

    # ---- application details (rqt_gui overrides) ----------------------------------------
    def application_icon(self):
        return None

    def window_title(self):
        return 'Default - rqt'

    # ---- settings / perspectives --------------------------------------------------------
    def _open_settings(self):
        from python_qt_binding.QtCore import QSettings
        if self.qsettings is None:
            self.qsettings = QSettings(QSettings.IniFormat, QSettings.UserScope, 'ros.org',
                                       self._settings_filename)

    def perspective_names(self):
        value = self.qsettings.value('perspectives')
        if value is None or value == '':
            names = []
        elif isinstance(value, str):
            names = [value]
        else:
            names = [str(v) for v in value]
        return [n for n in names if not n.startswith('@')]

    def _remember_perspective(self, name):
        if name.startswith('@'):
            return
        names = self.perspective_names()
        if name not in names:
            names.append(name)
            self.qsettings.setValue('perspectives', names)
        self.qsettings.setValue('current-perspective', name)
        if self.main_window is not None:
            self.main_window.setWindowTitle('%s - rqt' % name if self.window_title().endswith('rqt')
                                            else self.window_title())

    def _restore_window(self, standalone=False):
        geometry = self.qsettings.value('perspective/%s/mainwindow/geometry' % self.perspective)
        state = self.qsettings.value('perspective/%s/mainwindow/state' % self.perspective)
        if geometry is not None:
            self.main_window.restoreGeometry(geometry)
        elif standalone:
            self.main_window.adjustSize()
            size = self.main_window.size()
            self.main_window.resize(max(size.width(), 600), max(size.height(), 450))
        else:
            self.main_window.resize(600, 450)
            self.main_window.move(100, 100)
        if state is not None:
            self.main_window.restoreState(state)

    def save_perspective(self, name=None):
        name = name or self.perspective
        self.plugin_manager.save_perspective(name)
        self.qsettings.setValue('perspective/%s/mainwindow/geometry' % name, self.main_window.saveGeometry())
        self.qsettings.setValue('perspective/%s/mainwindow/state' % name, self.main_window.saveState())
        self.qsettings.sync()

    def _save_on_close(self):
        if self.perspective:
            self.save_perspective()
        self.plugin_manager.unload_all()

    def switch_perspective(self, name, clone=False):
        self.save_perspective()
        if not clone:
            self.plugin_manager.unload_all()
        self.perspective = name
        self._remember_perspective(name)
        if clone:
            self.save_perspective(name)
        else:
            self.plugin_manager.restore_perspective(name)
            state = self.qsettings.value('perspective/%s/mainwindow/state' % name)
            if state is not None:
                self.main_window.restoreState(state)
        if self.main_window.main is not None:
            self.main_window.fill_perspectives_menu()

    def remove_perspective(self, name):
        self.qsettings.remove('perspective/%s' % name)
        names = [n for n in self.perspective_names() if n != name]
        self.qsettings.setValue('perspectives', names)
        self.main_window.fill_perspectives_menu()

    def import_perspective(self, path):
        """Import a .perspective file into hidden perspective '@<basename>'; its name or None."""
        try:
            data = perspective_file.read_file(path)
        except (OSError, ValueError) as e:
            print('could not import perspective file "%s": %s' % (path, e), file=sys.stderr)
            return None
        name = '@' + os.path.splitext(os.path.basename(path))[0]
        try:
            perspective_file.import_group(self.qsettings, 'perspective/%s' % name, data)
        except Exception as e:
            print('could not import perspective file "%s": %s' % (path, e), file=sys.stderr)
            return None
        return name

    def export_perspective(self, path):
        self.save_perspective()
        data = perspective_file.export_group(self.qsettings, 'perspective/%s' % self.perspective)
        perspective_file.write_file(path, data)
        return path
