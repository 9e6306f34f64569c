"""qt_gui without a display or a master: plugin.xml parsing, --standalone matching, settings and
perspective files (QSettings on a temporary INI file)."""
import json

import pytest

from qt_gui.plugin_descriptor import PluginXmlError, match_plugins, parse_plugin_xml

XML = """<library path="src">
  <class name="RosGraph" type="rqt_graph.ros_graph.RosGraph" base_class_type="rqt_gui_py::Plugin">
    <description>Node Graph</description>
    <qtgui>
      <group><label>Introspection</label><icon type="theme">emblem-system</icon></group>
      <label>Node Graph</label>
      <icon type="theme">preferences-system-network</icon>
      <statustip>A graph.</statustip>
    </qtgui>
  </class>
  <class name="Cpp" type="pkg::Cpp" base_class_type="rqt_gui_cpp::Plugin"/>
</library>
"""


def test_plugin_xml_fields(tmp_path):
    p = tmp_path / 'plugin.xml'
    p.write_text(XML)
    (d,) = parse_plugin_xml(str(p), 'rqt_graph', 'rqt_gui_py::Plugin')
    assert d['plugin_id'] == 'rqt_graph/RosGraph'
    assert d['full_name'] == 'rqt_graph.ros_graph.RosGraph'
    assert (d['module_name'], d['class_attr']) == ('rqt_graph.ros_graph', 'RosGraph')
    assert d['library_path'] == str(tmp_path / 'src')
    assert d['label'] == 'Node Graph' and d['statustip'] == 'A graph.'
    assert d['icon'] == {'type': 'theme', 'value': 'preferences-system-network'}
    assert [g['label'] for g in d['groups']] == ['Introspection']
    every = parse_plugin_xml(str(p), 'rqt_graph')
    assert [x['full_name'] for x in every] == ['rqt_graph.ros_graph.RosGraph', 'pkg/Cpp']


def test_plugin_xml_errors_name_the_file(tmp_path):
    with pytest.raises(PluginXmlError, match='not found'):
        parse_plugin_xml(str(tmp_path / 'none.xml'), 'p')
    bad = tmp_path / 'plugin.xml'
    bad.write_text('<library><class')
    with pytest.raises(PluginXmlError, match='could not parse plugin.xml "%s"' % bad):
        parse_plugin_xml(str(bad), 'p')


def test_standalone_matching():
    ds = [{'plugin_id': 'rqt_graph/RosGraph', 'full_name': 'rqt_graph.ros_graph.RosGraph', 'class_type': ''},
          {'plugin_id': 'rqt_plot/Plot', 'full_name': 'rqt_plot.plot.Plot', 'class_type': ''},
          {'plugin_id': 'rqt_topic/TopicPlugin', 'full_name': 'rqt_topic.topic.Topic', 'class_type': ''}]
    assert [d['plugin_id'] for d in match_plugins(ds, 'rqt_graph')] == ['rqt_graph/RosGraph']
    assert [d['plugin_id'] for d in match_plugins(ds, 'RQT_PLOT.PLOT.PLOT')] == ['rqt_plot/Plot']
    assert [d['plugin_id'] for d in match_plugins(ds, 'rqt_topic.topic.Topic')] == ['rqt_topic/TopicPlugin']
    assert len(match_plugins(ds, 'rqt_')) == 3
    assert match_plugins(ds, 'nothing') == []


@pytest.fixture
def qsettings(tmp_path):
    from python_qt_binding.QtCore import QSettings
    return QSettings(str(tmp_path / 'rqt_gui.ini'), QSettings.IniFormat)


def test_settings_groups(qsettings):
    from qt_gui.settings import Settings
    s = Settings(qsettings, 'perspective/Default/pluginmanager/plugin__a__B__1/plugin')
    s.set_value('flag', True)
    s.set_value('n', 3)
    sub = s.get_settings('sub')
    sub.set_value('x', 'y')
    assert s.contains('flag') and not s.contains('none')
    assert sorted(s.child_keys()) == ['flag', 'n'] and s.child_groups() == ['sub']
    assert sorted(s.all_keys()) == ['flag', 'n', 'sub/x']
    assert s.value('none', 'default') == 'default'
    s.remove('n')
    assert sorted(s.child_keys()) == ['flag']


def test_perspective_file_round_trip(qsettings, tmp_path):
    from python_qt_binding.QtCore import QByteArray
    from qt_gui import perspective_file
    qsettings.setValue('perspective/Default/mainwindow/state', QByteArray(b'\x00\x01ab'))
    qsettings.setValue('perspective/Default/pluginmanager/running-plugins', {'rqt_plot/Plot': [1]})
    qsettings.setValue('perspective/Default/pluginmanager/plugin__rqt_plot__Plot__1/plugin/topics', "['/x']")
    data = perspective_file.export_group(qsettings, 'perspective/Default')
    path = str(tmp_path / 'p.perspective')
    perspective_file.write_file(path, data)
    raw = json.load(open(path))
    state = raw['groups']['mainwindow']['keys']['state']
    assert state['type'] == 'repr(QByteArray.hex)'
    assert state['repr(QByteArray.hex)'] == "QtCore.QByteArray(b'00016162')"
    assert raw['groups']['pluginmanager']['keys']['running-plugins'] == \
        {'type': 'repr', 'repr': "{'rqt_plot/Plot': [1]}"}
    perspective_file.import_group(qsettings, 'perspective/@p', perspective_file.read_file(path))
    assert bytes(qsettings.value('perspective/@p/mainwindow/state')) == b'\x00\x01ab'
    assert qsettings.value('perspective/@p/pluginmanager/running-plugins') == {'rqt_plot/Plot': [1]}
    with pytest.raises(ValueError, match='unknown serialization type "pickle"'):
        perspective_file.import_group(qsettings, 'perspective/@q', {'keys': {'a': {'type': 'pickle'}}})


def test_running_plugins_value():
    from qt_gui.plugin_manager import running_plugins_value
    assert running_plugins_value({'a/B': ['1', 2]}) == {'a/B': [1, 2]}
    assert running_plugins_value("{'a/B': [1]}") == {'a/B': [1]}
    assert running_plugins_value(None) == {} and running_plugins_value('junk') == {}
