"""The provider of Python rqt plugins (`rqt_gui_py::Plugin`: they need a ROS master and one rospy
node per process). rqt_gui finds it as the original does, through the plugin framework: this
package's plugin.xml exports it with base class `rqt_gui_py::PluginProvider`."""
import os
import socket
import sys

from qt_gui.plugin_provider import PluginLoadError
from rqt_gui.rospkg_plugin_provider import RospkgPluginProvider

_node_started = False


def master_reachable(timeout=1.0):
    import rosgraph
    old = socket.getdefaulttimeout()
    socket.setdefaulttimeout(timeout)
    try:
        rosgraph.Master('/rqt_gui').getSystemState()
        return True
    except Exception:
        return False
    finally:
        socket.setdefaulttimeout(old)


def wait_for_master():
    """True once a master answers; with a Qt application a modal box lets the user abort."""
    if master_reachable():
        return True
    print('RosPyPluginProvider: waiting for the ROS master at %s' % os.environ.get('ROS_MASTER_URI'),
          file=sys.stderr, flush=True)
    from python_qt_binding.QtCore import QTimer
    from python_qt_binding.QtWidgets import QApplication, QMessageBox
    if QApplication.instance() is None:
        return False
    box = QMessageBox(QMessageBox.Question, 'Waiting for ROS master',
                      "Could not find ROS master. Either start a 'roscore' or abort loading the plugin.",
                      QMessageBox.Abort)
    timer = QTimer(box)

    def poll():
        if master_reachable(0.2):
            box.done(QMessageBox.Ok)
    timer.timeout.connect(poll)
    timer.start(100)
    result = box.exec_()
    timer.stop()
    return result == QMessageBox.Ok


def init_node():
    global _node_started
    if _node_started:
        return
    import rospy
    rospy.init_node('rqt_gui_py_node_%d' % os.getpid(), disable_signals=True)
    _node_started = True


class RosPyPluginProvider(RospkgPluginProvider):

    def __init__(self, rospack=None):
        super(RosPyPluginProvider, self).__init__('rqt_gui', 'rqt_gui_py::Plugin', rospack)

    def load_class(self, descriptor):
        if not wait_for_master():
            raise PluginLoadError('could not find the ROS master at %s (start a roscore)'
                                  % os.environ.get('ROS_MASTER_URI'))
        init_node()
        return super(RosPyPluginProvider, self).load_class(descriptor)
