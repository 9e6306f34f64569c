"""rqt_gui main: qt_gui's main with the ROS plugin providers and ROS argument handling."""
import os
import sys

from qt_gui.main import Main as Base


class Main(Base):

    def __init__(self, filename=None, ros_pack=None, settings_filename='rqt_gui'):
        super(Main, self).__init__(invoked_filename=filename, settings_filename=settings_filename)
        self._ros_pack = ros_pack

    def main(self, argv=None, standalone=None, plugin_argument_provider=None):
        import rospy
        argv = rospy.myargv(list(sys.argv if argv is None else argv))
        if 'ROS_PACKAGE_PATH' not in os.environ:
            print('rqt_gui: ROS_PACKAGE_PATH is not set (source your workspace\'s setup.bash)',
                  file=sys.stderr)
            return 1
        return super(Main, self).main(argv, standalone=standalone,
                                      plugin_argument_provider=plugin_argument_provider)

    def create_providers(self):
        """As the original: the providers that packages export for rqt_gui (rqt_gui_py's
        RosPyPluginProvider) found through the plugin framework, and plain qt_gui plugins."""
        from qt_gui.recursive_plugin_provider import RecursivePluginProvider
        from rqt_gui.rospkg_plugin_provider import RospkgPluginProvider
        if self._ros_pack is None:
            from rospkg import RosPack
            self._ros_pack = RosPack()
        providers = RospkgPluginProvider('rqt_gui', 'rqt_gui_py::PluginProvider', self._ros_pack)
        return [RecursivePluginProvider(providers, context=self._ros_pack),
                RospkgPluginProvider('qt_gui', 'qt_gui_py::Plugin', self._ros_pack)]

    def application_icon(self):
        try:
            path = os.path.join(self._ros_pack.get_path('rqt_gui'), 'resource', 'rqt.png')
        except Exception:
            return None
        return path if os.path.isfile(path) else None
