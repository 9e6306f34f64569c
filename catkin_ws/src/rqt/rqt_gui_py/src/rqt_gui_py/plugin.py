"""rqt_gui_py.plugin.Plugin: base class of Python rqt plugins (rospy is initialised for them)."""
from qt_gui.plugin import Plugin as Base


class Plugin(Base):

    def __init__(self, context):
        super(Plugin, self).__init__(context)

    def shutdown_plugin(self):
        pass

    def save_settings(self, plugin_settings, instance_settings):
        pass

    def restore_settings(self, plugin_settings, instance_settings):
        pass
