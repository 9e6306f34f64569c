"""rqt_reconfigure plugin `ParamPlugin` ("Dynamic Reconfigure"): edit dynamic_reconfigure servers."""
import sys
import threading

from python_qt_binding.QtCore import Qt, Signal
from python_qt_binding.QtWidgets import (QCheckBox, QComboBox, QFileDialog, QFormLayout, QGroupBox,
                                         QHBoxLayout, QLabel, QLineEdit, QListWidget, QPushButton,
                                         QScrollArea, QSlider, QSplitter, QVBoxLayout, QWidget)
from rqt_gui_py.plugin import Plugin

from rqt_reconfigure.param_model import (ParamValueError, bound_text, editor_kind, enum_items,
                                         filter_servers, flatten_groups, parse_value, slider_enabled,
                                         slider_to_value, value_to_slider)


class NodeEditor(QWidget):
    """Editors for one server's parameters; `changed(name, value)` when the user edits one."""
    changed = Signal(str, object)

    def __init__(self, name, description, config, parent=None):
        super(NodeEditor, self).__init__(parent)
        self.name = name
        self.editors = {}
        self._setting = False
        layout = QVBoxLayout(self)
        title = QHBoxLayout()
        title.addWidget(QLabel('<b>%s</b>' % name), 1)
        self.save_button = QPushButton('Save')
        self.load_button = QPushButton('Load')
        title.addWidget(self.save_button)
        title.addWidget(self.load_button)
        layout.addLayout(title)
        groups = {}
        for path, p in flatten_groups(description):
            key = path[1:]
            if key not in groups:
                box = QGroupBox('/'.join(key)) if key else QWidget()
                form = QFormLayout(box)
                layout.addWidget(box)
                groups[key] = form
            self._add(groups[key], p, config.get(p['name'], p.get('default')))
        layout.addStretch(1)

    def _add(self, form, p, value):
        kind = editor_kind(p)
        name = p['name']
        row = QWidget()
        h = QHBoxLayout(row)
        h.setContentsMargins(0, 0, 0, 0)
        if kind == 'enum':
            w = QComboBox()
            items = enum_items(p)
            for n, v, d in items:
                w.addItem('%s (%s)' % (n, v), v)
            w.currentIndexChanged.connect(lambda i, w=w, n=name: self._emit(n, w.itemData(i)))
            h.addWidget(w)
        elif kind == 'bool':
            w = QCheckBox()
            w.toggled.connect(lambda on, n=name: self._emit(n, bool(on)))
            h.addWidget(w)
        elif kind == 'str':
            w = QLineEdit()
            w.editingFinished.connect(lambda w=w, n=name: self._emit(n, w.text()))
            h.addWidget(w)
        else:
            h.addWidget(QLabel(bound_text(p['min'])))
            slider = QSlider(Qt.Horizontal)
            slider.setRange(0, 1000)
            slider.setEnabled(slider_enabled(p))
            h.addWidget(slider, 1)
            h.addWidget(QLabel(bound_text(p['max'])))
            w = QLineEdit()
            w.setMaximumWidth(100)
            h.addWidget(w)
            w.slider = slider

            def edited(w=w, p=p):
                try:
                    v = parse_value(p, w.text())
                except ParamValueError as e:
                    self.error(str(e))
                    return
                self._emit(p['name'], v)
            w.editingFinished.connect(edited)
            slider.sliderReleased.connect(lambda s=slider, p=p: self._emit(p['name'], slider_to_value(p, s.value())))
        w.setObjectName(name)
        w.setToolTip(p.get('description', ''))
        form.addRow(name, row)
        self.editors[name] = (p, w)
        self.set_value(name, value)

    def _emit(self, name, value):
        if not self._setting:
            self.changed.emit(name, value)

    def set_value(self, name, value):
        if name not in self.editors:
            return
        p, w = self.editors[name]
        kind = editor_kind(p)
        self._setting = True
        try:
            if kind == 'enum':
                i = w.findData(value)
                if i >= 0:
                    w.setCurrentIndex(i)
            elif kind == 'bool':
                w.setChecked(bool(value))
            elif kind == 'str':
                w.setText(str(value))
            else:
                w.setText(str(value))
                if slider_enabled(p):
                    w.slider.setValue(value_to_slider(p, value))
        finally:
            self._setting = False

    def value(self, name):
        p, w = self.editors[name]
        kind = editor_kind(p)
        if kind == 'enum':
            return w.currentData()
        if kind == 'bool':
            return w.isChecked()
        return parse_value(p, w.text()) if kind != 'str' else w.text()

    def error(self, text):
        print('rqt_reconfigure: %s' % text, file=sys.stderr, flush=True)
        label = self.window().findChild(QLabel, 'status_label')
        if label is not None:
            label.setText('ERROR: ' + text)


class ParamWidget(QWidget):
    loaded = Signal(str, object, object, object)     # name, client, description, config or error

    def __init__(self, parent=None):
        super(ParamWidget, self).__init__(parent)
        self.setObjectName('ParamWidgetUi')
        self.setWindowTitle('Dynamic Reconfigure')
        self.filter_line_edit = QLineEdit()
        self.filter_line_edit.setPlaceholderText('Filter key:')
        self.refresh_button = QPushButton('Refresh')
        self.node_list = QListWidget()
        self.node_list.setObjectName('node_list')
        self.editors_area = QWidget()
        self.editors_layout = QVBoxLayout(self.editors_area)
        self.editors_layout.addStretch(1)
        scroll = QScrollArea()
        scroll.setWidgetResizable(True)
        scroll.setWidget(self.editors_area)
        left = QWidget()
        lv = QVBoxLayout(left)
        lv.addWidget(self.filter_line_edit)
        lv.addWidget(self.node_list, 1)
        lv.addWidget(self.refresh_button)
        split = QSplitter()
        split.addWidget(left)
        split.addWidget(scroll)
        split.setStretchFactor(1, 3)
        self.status = QLabel()
        self.status.setObjectName('status_label')
        layout = QVBoxLayout(self)
        layout.addWidget(split, 1)
        layout.addWidget(self.status)


class ParamPlugin(Plugin):

    def __init__(self, context):
        super(ParamPlugin, self).__init__(context)
        self.setObjectName('Reconfigure')
        self._widget = w = ParamWidget()
        if context.serial_number() > 1:
            w.setWindowTitle(w.windowTitle() + (' (%d)' % context.serial_number()))
        self._servers = []
        self._clients = {}
        self.node_editors = {}
        w.refresh_button.clicked.connect(self.refresh)
        w.filter_line_edit.textChanged.connect(self._fill_list)
        w.node_list.itemChanged.connect(self._item_changed)
        w.loaded.connect(self._loaded)
        context.add_widget(w)
        self._initial = [a for a in context.argv() if not a.startswith('-')]
        self.refresh()
        for name in self._initial:
            self.open_node(name if name.startswith('/') else '/' + name)

    def refresh(self):
        import dynamic_reconfigure
        try:
            self._servers = sorted(dynamic_reconfigure.find_reconfigure_services())
        except Exception as e:
            self._report('could not list the reconfigure servers: %s' % e)
            self._servers = []
        self._fill_list()

    def _fill_list(self, *_):
        lst = self._widget.node_list
        lst.blockSignals(True)
        lst.clear()
        for name in filter_servers(self._servers, self._widget.filter_line_edit.text()):
            lst.addItem(name)
            item = lst.item(lst.count() - 1)
            item.setFlags(item.flags() | Qt.ItemIsUserCheckable)
            item.setCheckState(Qt.Checked if name in self.node_editors or name in self._clients else Qt.Unchecked)
        lst.blockSignals(False)

    def _item_changed(self, item):
        if item.checkState() == Qt.Checked:
            self.open_node(item.text())
        else:
            self.close_node(item.text())

    def open_node(self, name):
        if name in self._clients:
            return

        def work():
            import dynamic_reconfigure.client
            try:
                client = dynamic_reconfigure.client.Client(name, timeout=5.0)
                desc = client.get_group_descriptions()
                config = client.get_configuration(timeout=5.0)
                self._widget.loaded.emit(name, client, desc, config)
            except Exception as e:
                self._widget.loaded.emit(name, None, None, 'could not connect to "%s": %s' % (name, e))
        self._clients[name] = None
        threading.Thread(target=work, daemon=True).start()

    def _loaded(self, name, client, desc, config):
        if client is None:
            self._clients.pop(name, None)
            self._report(config)
            return
        self._clients[name] = client
        ed = NodeEditor(name, desc, dict(config or {}))
        ed.changed.connect(lambda n, v, name=name: self.set_param(name, n, v))
        ed.save_button.clicked.connect(lambda _c=False, name=name: self.save_yaml(name))
        ed.load_button.clicked.connect(lambda _c=False, name=name: self.load_yaml(name))
        self._widget.editors_layout.insertWidget(self._widget.editors_layout.count() - 1, ed)
        self.node_editors[name] = ed
        self._fill_list()

    def close_node(self, name):
        client = self._clients.pop(name, None)
        if client is not None:
            client.close()
        ed = self.node_editors.pop(name, None)
        if ed is not None:
            ed.setParent(None)
            ed.deleteLater()

    def set_param(self, node, name, value):
        client = self._clients.get(node)
        if client is None:
            return

        def work():
            try:
                client.update_configuration({name: value})
            except Exception as e:
                print('rqt_reconfigure: could not set %s/%s: %s' % (node, name, e), file=sys.stderr)
        threading.Thread(target=work, daemon=True).start()

    def save_yaml(self, node, path=None):
        import yaml
        client = self._clients.get(node)
        if client is None:
            return
        path = path or QFileDialog.getSaveFileName(self._widget, 'Save parameters to file...', '.',
                                                   'YAML file {.yaml} (*.yaml)')[0]
        if path:
            with open(path, 'w') as f:
                yaml.dump(dict(client.get_configuration(timeout=5.0)), f)

    def load_yaml(self, node, path=None):
        import yaml
        client = self._clients.get(node)
        if client is None:
            return
        path = path or QFileDialog.getOpenFileName(self._widget, 'Load from File', '.', 'YAML file {.yaml} (*.yaml)')[0]
        if not path:
            return
        try:
            with open(path) as f:
                docs = [d for d in yaml.safe_load_all(f) if d]
        except (OSError, yaml.YAMLError) as e:
            self._report('could not load "%s": %s' % (path, e))
            return
        for d in docs:
            d = {k: v for k, v in d.items() if k not in ('groups',)}
            config = client.update_configuration(d)
            ed = self.node_editors.get(node)
            for k, v in dict(config).items():
                if ed:
                    ed.set_value(k, v)

    def _report(self, line):
        self._widget.status.setText('ERROR: ' + line)
        print('rqt_reconfigure: %s' % line, file=sys.stderr, flush=True)

    def save_settings(self, plugin_settings, instance_settings):
        instance_settings.set_value('open_nodes', repr(sorted(self.node_editors)))

    def restore_settings(self, plugin_settings, instance_settings):
        if self._initial:
            return
        try:
            names = eval(str(instance_settings.value('open_nodes', '[]')))
        except Exception:
            names = []
        for n in names:
            if n in self._servers:
                self.open_node(n)

    def shutdown_plugin(self):
        for name in list(self._clients):
            self.close_node(name)
