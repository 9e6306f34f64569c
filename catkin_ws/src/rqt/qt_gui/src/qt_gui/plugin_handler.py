"""One running plugin instance: its object, context, docks and toolbars."""
import sys
import traceback

from python_qt_binding.QtCore import Qt

from qt_gui.dock_widget import DockWidget
from qt_gui.plugin_context import PluginContext


def settings_name(plugin_id):
    return 'plugin__' + plugin_id.replace('/', '__')


class PluginHandler(object):

    def __init__(self, manager, descriptor, provider, serial, argv):
        self.manager = manager
        self.descriptor = descriptor
        self.provider = provider
        self.plugin_id = descriptor['plugin_id']
        self.serial = serial
        self.argv = argv or []
        self.instance = None
        self.plugin_class = None
        self.context = PluginContext(self)
        self.docks = []
        self.toolbars = []

    @property
    def name(self):
        return '%s__%d' % (settings_name(self.plugin_id), self.serial)

    def label(self):
        label = self.descriptor['label']
        return label if self.serial <= 1 else '%s (%d)' % (label, self.serial)

    # ---- widgets ------------------------------------------------------------------------
    def add_widget(self, widget):
        mw = self.manager.main_window
        name = '%s__%d__%s' % (self.plugin_id.replace('/', '__'), self.serial, widget.objectName())
        if mw.findChild(DockWidget, name) is not None:
            print('PluginHandler.add_widget() duplicate object name "%s", assign unique object '
                  'names before adding widgets!' % name, file=sys.stderr)
        configure = self._configure_callback()
        dock = DockWidget(widget.windowTitle() or self.descriptor['label'], configure=configure,
                          hide_title=self.manager.hide_title,
                          closable=not self.manager.lock_perspective)
        dock.setObjectName(name)
        dock.setWidget(widget)
        if not widget.windowIcon().isNull():
            dock.setWindowIcon(widget.windowIcon())
        widget.windowTitleChanged.connect(dock.setWindowTitle)
        widget.windowIconChanged.connect(dock.setWindowIcon)
        if self.manager.freeze_layout:
            dock.setFeatures(QDockWidget_NoFeatures())
        dock.closed.connect(lambda _d: self.manager.unload_plugin(self))
        mw.addDockWidget(Qt.BottomDockWidgetArea, dock)
        dock.show()
        self.docks.append(dock)
        self.manager.widget_added(self, dock)

    def _configure_callback(self):
        cls = self.plugin_class
        if cls is None or not hasattr(cls, 'trigger_configuration'):
            return None
        return lambda: self.call('trigger_configuration')

    def remove_widget(self, widget):
        for dock in list(self.docks):
            if dock.widget() is widget:
                self.docks.remove(dock)
                dock.close_by_framework()
                self.manager.main_window.removeDockWidget(dock)
                dock.deleteLater()

    def add_toolbar(self, toolbar):
        toolbar.setObjectName('%s__%d__%s' % (self.plugin_id.replace('/', '__'), self.serial,
                                              toolbar.objectName()))
        self.manager.main_window.addToolBar(Qt.TopToolBarArea, toolbar)
        self.toolbars.append(toolbar)

    def remove_toolbar(self, toolbar):
        if toolbar in self.toolbars:
            self.toolbars.remove(toolbar)
            self.manager.main_window.removeToolBar(toolbar)

    def remove_all(self):
        for dock in list(self.docks):
            self.remove_widget(dock.widget())
        for tb in list(self.toolbars):
            self.remove_toolbar(tb)

    # ---- life cycle ---------------------------------------------------------------------
    def call(self, method, *args):
        """Call an optional plugin method; exceptions are logged, never raised."""
        fn = getattr(self.instance, method, None)
        if fn is None:
            return
        try:
            fn(*args)
        except Exception:
            print('PluginHandler: plugin "%s" raised in %s():\n%s' % (
                self.plugin_id, method, traceback.format_exc()), file=sys.stderr)


def QDockWidget_NoFeatures():
    from python_qt_binding.QtWidgets import QDockWidget
    return QDockWidget.NoDockWidgetFeatures
