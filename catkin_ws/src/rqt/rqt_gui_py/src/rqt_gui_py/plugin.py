"""rqt_gui_py.plugin.Plugin: base class of Python rqt plugins (rospy is initialised for them by
RosPyPluginProvider); shutdown_plugin, save_settings and restore_settings are qt_gui's."""
from qt_gui.plugin import Plugin as Base


class Plugin(Base):

    def __init__(self, context):
        super(Plugin, self).__init__(context)
