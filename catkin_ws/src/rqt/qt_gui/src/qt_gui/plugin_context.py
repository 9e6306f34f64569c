"""qt_gui.plugin_context.PluginContext: what a plugin's __init__ receives."""
from python_qt_binding.QtCore import QObject


class PluginContext(QObject):

    def __init__(self, handler):
        super(PluginContext, self).__init__(handler.manager)
        self._handler = handler
        self.setObjectName('PluginContext')

    def serial_number(self):
        return self._handler.serial

    def argv(self):
        return list(self._handler.argv)

    def add_widget(self, widget):
        self._handler.add_widget(widget)

    def remove_widget(self, widget):
        self._handler.remove_widget(widget)

    def add_toolbar(self, toolbar):
        self._handler.add_toolbar(toolbar)

    def remove_toolbar(self, toolbar):
        self._handler.remove_toolbar(toolbar)

    def close_plugin(self):
        self._handler.manager.unload_plugin(self._handler)

    def reload_plugin(self):
        self._handler.manager.reload_plugin(self._handler)
