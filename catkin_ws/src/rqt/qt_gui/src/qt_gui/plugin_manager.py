"""Discovered plugins, running instances, and saving/restoring them in perspectives."""
import ast
import sys
import traceback

from python_qt_binding.QtCore import QObject, Signal

from qt_gui.plugin_handler import PluginHandler, settings_name
from qt_gui.settings import Settings


def running_plugins_value(value):
    """`running-plugins` as a dict id -> [serials], whatever QSettings handed back."""
    if value is None or value == '':
        return {}
    if isinstance(value, str):
        try:
            value = ast.literal_eval(value)
        except (ValueError, SyntaxError):
            return {}
    if not isinstance(value, dict):
        return {}
    out = {}
    for pid, serials in value.items():
        if not isinstance(serials, (list, tuple)):
            serials = [serials]
        out[str(pid)] = [int(s) for s in serials]
    return out


class PluginManager(QObject):
    plugins_changed = Signal()
    message = Signal(str)

    def __init__(self, main_window, qsettings, providers, standalone=False, lock_perspective=False,
                 freeze_layout=False, hide_title=False):
        super(PluginManager, self).__init__(main_window)
        self.main_window = main_window
        self.qsettings = qsettings
        self.providers = providers
        self.standalone = standalone
        self.lock_perspective = lock_perspective
        self.freeze_layout = freeze_layout
        self.hide_title = hide_title
        self.plugins = {}      # plugin id -> (descriptor, provider)
        self.running = {}      # (plugin id, serial) -> PluginHandler
        self.errors = []

    # ---- discovery ----------------------------------------------------------------------
    def discover(self):
        self.plugins = {}
        for provider in self.providers:
            for d in provider.discover():
                self.plugins.setdefault(d['plugin_id'], (d, provider))
            for line in provider.errors:
                self.report(line)
        return [d for d, _ in self.plugins.values()]

    def descriptors(self):
        return sorted((d for d, _ in self.plugins.values()), key=lambda d: d['full_name'])

    def report(self, line):
        self.errors.append(line)
        print(line, file=sys.stderr, flush=True)
        self.message.emit(line)

    # ---- instances ----------------------------------------------------------------------
    def next_serial(self, plugin_id):
        used = {s for (pid, s) in self.running if pid == plugin_id}
        n = 1
        while n in used:
            n += 1
        return n

    def load_plugin(self, plugin_id, serial=None, argv=None, perspective=None):
        if plugin_id not in self.plugins:
            self.report('PluginManager.load_plugin() could not load plugin "%s": no such plugin'
                        % plugin_id)
            return None
        descriptor, provider = self.plugins[plugin_id]
        if serial is None:
            serial = 0 if self.standalone else self.next_serial(plugin_id)
        handler = PluginHandler(self, descriptor, provider, serial, argv)
        try:
            handler.plugin_class = provider.load_class(descriptor)
            handler.instance = provider.instantiate(handler.plugin_class, handler.context)
        except Exception as e:
            handler.remove_all()
            detail = traceback.format_exc()
            print('PluginManager._load_plugin() could not load plugin "%s":\n%s' % (plugin_id, detail),
                  file=sys.stderr, flush=True)
            self.report('could not load plugin "%s": %s: %s' % (plugin_id, type(e).__name__, e))
            return None
        self.running[(plugin_id, serial)] = handler
        if perspective is not None:
            self._restore_plugin_settings(handler, perspective)
        else:
            handler.call('restore_settings', self.plugin_settings(handler),
                         Settings(self.qsettings, '__unsaved__/%s' % handler.name))
        self.plugins_changed.emit()
        return handler

    def unload_plugin(self, handler, save_to=None):
        key = (handler.plugin_id, handler.serial)
        if self.running.get(key) is not handler:
            return
        if save_to is not None:
            self._save_plugin_settings(handler, save_to)
        handler.call('shutdown_plugin')
        handler.remove_all()
        handler.provider.unload(handler.instance)
        del self.running[key]
        self.plugins_changed.emit()

    def reload_plugin(self, handler):
        pid, serial, argv = handler.plugin_id, handler.serial, handler.argv
        self.unload_plugin(handler)
        self.load_plugin(pid, serial, argv)

    def unload_all(self, save_to=None):
        for handler in list(self.running.values()):
            self.unload_plugin(handler, save_to)

    def widget_added(self, handler, dock):
        pass

    # ---- settings -----------------------------------------------------------------------
    def plugin_settings(self, handler):
        return Settings(self.qsettings,
                        'global/pluginmanager/%s/plugin' % settings_name(handler.plugin_id))

    def instance_group(self, handler, perspective):
        return 'perspective/%s/pluginmanager/%s' % (perspective, handler.name)

    def _save_plugin_settings(self, handler, perspective):
        group = self.instance_group(handler, perspective)
        self.qsettings.remove(group)
        handler.call('save_settings', self.plugin_settings(handler),
                     Settings(self.qsettings, group + '/plugin'))
        for dock in handler.docks:
            inner = dock.objectName().split('__')[-1]
            base = '%s/dock_widget__%s/' % (group, inner)
            self.qsettings.setValue(base + 'dock_widget_title', dock.windowTitle())
            self.qsettings.setValue(base + 'dockable', True)
            self.qsettings.setValue(base + 'parent', None)

    def _restore_plugin_settings(self, handler, perspective):
        group = self.instance_group(handler, perspective)
        handler.call('restore_settings', self.plugin_settings(handler),
                     Settings(self.qsettings, group + '/plugin'))

    def save_perspective(self, perspective):
        """Settings of every running plugin and which are running (the window is saved by the
        caller)."""
        base = 'perspective/%s/pluginmanager' % perspective
        self.qsettings.remove(base)
        running = {}
        for (pid, serial), handler in sorted(self.running.items()):
            running.setdefault(pid, []).append(serial)
            self._save_plugin_settings(handler, perspective)
        self.qsettings.setValue(base + '/running-plugins', running)

    def restore_perspective(self, perspective):
        """Start the plugins a perspective lists, each with its saved settings."""
        running = running_plugins_value(
            self.qsettings.value('perspective/%s/pluginmanager/running-plugins' % perspective))
        for pid in sorted(running):
            for serial in sorted(running[pid]):
                if (pid, serial) in self.running:
                    continue
                self.load_plugin(pid, serial, perspective=perspective)
