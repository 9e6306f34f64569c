"""Plugin packages written by the tests (not in the workspace, so nobody else's Plugins menu shows
them): one written from the ROS wiki tutorial "Writing a Python Plugin", and broken ones."""
import os

TUTORIAL_PACKAGE_XML = """<?xml version="1.0"?>
<package format="2">
  <name>rqt_mypkg</name>
  <version>0.0.1</version>
  <description>The rqt_mypkg package</description>
  <maintainer email="user@example.org">user</maintainer>
  <license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend>
  <exec_depend>rospy</exec_depend>
  <exec_depend>rqt_gui</exec_depend>
  <exec_depend>rqt_gui_py</exec_depend>
  <export>
    <rqt_gui plugin="${prefix}/plugin.xml"/>
  </export>
</package>
"""

TUTORIAL_PLUGIN_XML = """<library path="src">
  <class name="My Plugin" type="rqt_mypkg.my_module.MyPlugin" base_class_type="rqt_gui_py::Plugin">
    <description>
      An example Python GUI plugin to create a great user interface.
    </description>
    <qtgui>
      <group>
        <label>Examples</label>
      </group>
      <!-- optional grouping...
      <group>
        <label>Group</label>
      </group>
      -->
      <label>My first Python Plugin</label>
      <icon type="theme">system-help</icon>
      <statustip>Great user interface to provide real value.</statustip>
    </qtgui>
  </class>
</library>
"""

TUTORIAL_MODULE = '''import os
import rospy
import rospkg

from qt_gui.plugin import Plugin
from python_qt_binding import loadUi
from python_qt_binding.QtWidgets import QWidget


class MyPlugin(Plugin):

    def __init__(self, context):
        super(MyPlugin, self).__init__(context)
        # Give QObjects reasonable names
        self.setObjectName('MyPlugin')

        # Process standalone plugin command-line arguments
        from argparse import ArgumentParser
        parser = ArgumentParser()
        # Add argument(s) to the parser.
        parser.add_argument("-q", "--quiet", action="store_true",
                      dest="quiet",
                      help="Put plugin in silent mode")
        args, unknowns = parser.parse_known_args(context.argv())
        if not args.quiet:
            print('arguments: ', args)
            print('unknowns: ', unknowns)

        # Create QWidget
        self._widget = QWidget()
        # Get path to UI file which should be in the "resource" folder of this package
        ui_file = os.path.join(rospkg.RosPack().get_path('rqt_mypkg'), 'resource', 'MyPlugin.ui')
        # Extend the widget with all attributes and children from UI file
        loadUi(ui_file, self._widget)
        # Give QObjects reasonable names
        self._widget.setObjectName('MyPluginUi')
        # Show _widget.windowTitle on left-top of each plugin (when
        # it's set in _widget). This is useful when you open multiple
        # plugins at once. Also if you open multiple instances of your
        # plugin at once, these lines add number to make it easy to
        # tell from pane to pane.
        if context.serial_number() > 1:
            self._widget.setWindowTitle(self._widget.windowTitle() + (' (%d)' % context.serial_number()))
        # Add widget to the user interface
        context.add_widget(self._widget)
        self.saved = None

    def shutdown_plugin(self):
        # TODO unregister all publishers here
        pass

    def save_settings(self, plugin_settings, instance_settings):
        # TODO save intrinsic configuration, usually using:
        instance_settings.set_value('k', self._widget.windowTitle())

    def restore_settings(self, plugin_settings, instance_settings):
        # TODO restore intrinsic configuration, usually using:
        self.saved = instance_settings.value('k')

    #def trigger_configuration(self):
        # Comment in to signal that the plugin has a way to configure
        # This will enable a setting button (gear icon) in each dock widget title bar
        # Usually used to open a modal configuration dialog
'''

TUTORIAL_UI = """<?xml version="1.0" encoding="UTF-8"?>
<ui version="4.0">
 <class>MyPluginWidget</class>
 <widget class="QWidget" name="MyPluginWidget">
  <property name="geometry"><rect><x>0</x><y>0</y><width>400</width><height>300</height></rect></property>
  <property name="windowTitle"><string>My Plugin Title</string></property>
  <layout class="QVBoxLayout" name="verticalLayout">
   <item>
    <widget class="QPushButton" name="Test">
     <property name="text"><string>Original Name</string></property>
    </widget>
   </item>
  </layout>
 </widget>
 <resources/>
 <connections/>
</ui>
"""

BROKEN_PACKAGE_XML = TUTORIAL_PACKAGE_XML.replace('rqt_mypkg', 'rqt_broken')

BROKEN_PLUGIN_XML = """<library path="src">
  <class name="Raises" type="rqt_broken.broken.Raises" base_class_type="rqt_gui_py::Plugin">
    <description>raises in __init__</description>
    <qtgui><group><label>Examples</label></group><label>Raises</label></qtgui>
  </class>
  <class name="Missing" type="rqt_broken.broken.NoSuchClass" base_class_type="rqt_gui_py::Plugin">
    <description>names a class that does not exist</description>
    <qtgui><group><label>Examples</label></group><label>Missing class</label></qtgui>
  </class>
</library>
"""

BROKEN_MODULE = '''from python_qt_binding.QtWidgets import QLabel
from rqt_gui_py.plugin import Plugin


class Raises(Plugin):
    def __init__(self, context):
        super(Raises, self).__init__(context)
        w = QLabel('half built')
        w.setObjectName('HalfUi')
        context.add_widget(w)
        raise RuntimeError('boom in __init__')
'''

BAD_XML_PACKAGE_XML = TUTORIAL_PACKAGE_XML.replace('rqt_mypkg', 'rqt_badxml')


def _write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, 'w') as f:
        f.write(text)


def write_packages(root):
    """Write the plugin packages under `root`; returns root (prepend it to ROS_PACKAGE_PATH)."""
    root = str(root)
    p = os.path.join(root, 'rqt_mypkg')
    _write(os.path.join(p, 'package.xml'), TUTORIAL_PACKAGE_XML)
    _write(os.path.join(p, 'plugin.xml'), TUTORIAL_PLUGIN_XML)
    _write(os.path.join(p, 'src', 'rqt_mypkg', '__init__.py'), '')
    _write(os.path.join(p, 'src', 'rqt_mypkg', 'my_module.py'), TUTORIAL_MODULE)
    _write(os.path.join(p, 'resource', 'MyPlugin.ui'), TUTORIAL_UI)
    b = os.path.join(root, 'rqt_broken')
    _write(os.path.join(b, 'package.xml'), BROKEN_PACKAGE_XML)
    _write(os.path.join(b, 'plugin.xml'), BROKEN_PLUGIN_XML)
    _write(os.path.join(b, 'src', 'rqt_broken', '__init__.py'), '')
    _write(os.path.join(b, 'src', 'rqt_broken', 'broken.py'), BROKEN_MODULE)
    x = os.path.join(root, 'rqt_badxml')
    _write(os.path.join(x, 'package.xml'), BAD_XML_PACKAGE_XML)
    _write(os.path.join(x, 'plugin.xml'), '<library><class name="A" type="a.b.A"')
    return root
