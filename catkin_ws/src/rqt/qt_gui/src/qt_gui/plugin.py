"""Base class of Python plugins (qt_gui.plugin.Plugin)."""
from python_qt_binding.QtCore import QObject


class Plugin(QObject):
    """A plugin: build widgets in __init__ and hand them to context.add_widget()."""

    def __init__(self, context):
        super(Plugin, self).__init__(context)
        self.setObjectName('Plugin')

    def shutdown_plugin(self):
        """Unregister publishers/subscribers and stop timers."""
        pass

    def save_settings(self, plugin_settings, instance_settings):
        pass

    def restore_settings(self, plugin_settings, instance_settings):
        pass
