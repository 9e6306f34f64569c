"""rqt_console plugin `Console`: /rosout_agg messages with severity exclusion and highlighting."""
import sys
import threading

from python_qt_binding.QtCore import QAbstractTableModel, QModelIndex, Qt, QTimer
from python_qt_binding.QtGui import QBrush, QColor, QFont
from python_qt_binding.QtWidgets import (QCheckBox, QComboBox, QDialog, QDialogButtonBox,
                                         QFileDialog, QFormLayout, QHBoxLayout, QLabel, QLineEdit,
                                         QPushButton, QSpinBox, QTableView, QVBoxLayout, QWidget)
from rqt_gui_py.plugin import Plugin

from rqt_console.console_core import (COLUMNS, DEBUG, DEFAULT_LIMIT, ERROR, FATAL, INFO,
                                      SEVERITY_COLORS, SEVERITY_LABELS, WARN, ConsoleModel, Filter,
                                      Message, from_csv, to_csv)


class MessageTableModel(QAbstractTableModel):

    def __init__(self, core, parent=None):
        super(MessageTableModel, self).__init__(parent)
        self.core = core
        self.rows = []

    def refresh(self):
        self.beginResetModel()
        self.rows = self.core.visible()
        self.endResetModel()

    def rowCount(self, parent=QModelIndex()):
        return 0 if parent.isValid() else len(self.rows)

    def columnCount(self, parent=QModelIndex()):
        return len(COLUMNS)

    def headerData(self, section, orientation, role=Qt.DisplayRole):
        if role == Qt.DisplayRole and orientation == Qt.Horizontal:
            return COLUMNS[section]
        return None

    def data(self, index, role=Qt.DisplayRole):
        m = self.rows[index.row()]
        if role in (Qt.DisplayRole, Qt.ToolTipRole):
            return m.columns()[index.column()]
        if role == Qt.ForegroundRole and index.column() == 2:
            return QBrush(QColor(SEVERITY_COLORS.get(m.severity, 'black')))
        if role == Qt.FontRole and self.core.highlight and any(f.is_active() for f in self.core.highlight):
            if self.core.is_highlighted(m):
                f = QFont()
                f.setBold(True)
                return f
        return None


class ConsoleWidget(QWidget):

    def __init__(self, core, parent=None):
        super(ConsoleWidget, self).__init__(parent)
        self.setObjectName('ConsoleUi')
        self.setWindowTitle('Console')
        self.core = core
        self.model = MessageTableModel(core, self)
        self.table_view = QTableView()
        self.table_view.setObjectName('table_view')
        self.table_view.setModel(self.model)
        self.table_view.setSelectionBehavior(QTableView.SelectRows)
        self.table_view.horizontalHeader().setStretchLastSection(True)
        self.table_view.setColumnWidth(1, 320)
        self.pause_button = QPushButton('Pause')
        self.pause_button.setCheckable(True)
        self.clear_button = QPushButton('Clear')
        self.save_button = QPushButton('Save')
        self.load_button = QPushButton('Load')
        self.status_label = QLabel()
        bar = QHBoxLayout()
        bar.addWidget(self.status_label, 1)
        for b in (self.pause_button, self.clear_button, self.save_button, self.load_button):
            bar.addWidget(b)
        # exclude: ...with severities
        self.exclude_severity = Filter('severity')
        self.severity_boxes = {}
        ex = QHBoxLayout()
        ex.addWidget(QLabel('Exclude Messages... with severities:'))
        for sev in (DEBUG, INFO, WARN, ERROR, FATAL):
            cb = QCheckBox(SEVERITY_LABELS[sev])
            cb.setObjectName('exclude_%s_check_box' % SEVERITY_LABELS[sev].lower())
            cb.toggled.connect(self._filters_changed)
            self.severity_boxes[sev] = cb
            ex.addWidget(cb)
        ex.addStretch(1)
        # highlight: ...containing
        self.highlight_text = Filter('message')
        hl = QHBoxLayout()
        hl.addWidget(QLabel('Highlight Messages... containing:'))
        self.highlight_line_edit = QLineEdit()
        self.highlight_line_edit.setObjectName('highlight_line_edit')
        self.highlight_regex_check_box = QCheckBox('Regex')
        self.show_highlighted_only_check_box = QCheckBox('Show only highlighted rows')
        hl.addWidget(self.highlight_line_edit, 1)
        hl.addWidget(self.highlight_regex_check_box)
        hl.addWidget(self.show_highlighted_only_check_box)
        self.highlight_line_edit.textChanged.connect(self._filters_changed)
        self.highlight_regex_check_box.toggled.connect(self._filters_changed)
        self.show_highlighted_only_check_box.toggled.connect(self._filters_changed)
        core.exclude = [self.exclude_severity]
        core.highlight = [self.highlight_text]
        layout = QVBoxLayout(self)
        layout.addLayout(bar)
        layout.addWidget(self.table_view, 1)
        layout.addLayout(ex)
        layout.addLayout(hl)
        self.clear_button.clicked.connect(self.clear)
        self.save_button.clicked.connect(lambda: self.save())
        self.load_button.clicked.connect(lambda: self.load())
        self.refresh()

    def _filters_changed(self, *_):
        self.exclude_severity.severities = {s for s, cb in self.severity_boxes.items() if cb.isChecked()}
        self.highlight_text.text = self.highlight_line_edit.text()
        self.highlight_text.regex = self.highlight_regex_check_box.isChecked()
        self.core.show_highlighted_only = self.show_highlighted_only_check_box.isChecked()
        self.refresh()

    def refresh(self):
        self.model.refresh()
        self.status_label.setText(self.core.status_text(len(self.model.rows)))

    def clear(self):
        self.core.clear()
        self.refresh()

    def save(self, path=None):
        path = path or QFileDialog.getSaveFileName(self, 'Save to File', '.', 'rqt_console message file (*.csv)')[0]
        if path:
            with open(path, 'w') as f:
                f.write(to_csv(list(reversed(self.core.messages))))

    def load(self, path=None):
        path = path or QFileDialog.getOpenFileName(self, 'Load File', '.', 'rqt_console message file (*.csv)')[0]
        if not path:
            return
        try:
            with open(path) as f:
                messages = from_csv(f.read())
        except (OSError, ValueError) as e:
            self.status_label.setText('ERROR: could not load "%s": %s' % (path, e))
            print('rqt_console: could not load "%s": %s' % (path, e), file=sys.stderr)
            return
        self.core.add(messages)
        self.refresh()


class Console(Plugin):

    def __init__(self, context):
        super(Console, self).__init__(context)
        self.setObjectName('Console')
        self._core = ConsoleModel(DEFAULT_LIMIT)
        self._widget = ConsoleWidget(self._core)
        if context.serial_number() > 1:
            self._widget.setWindowTitle(self._widget.windowTitle() + (' (%d)' % context.serial_number()))
        self._queue = []
        self._lock = threading.Lock()
        self._topic = '/rosout_agg'
        self._sub = None
        context.add_widget(self._widget)
        self._subscribe(self._topic)
        self._timer = QTimer(self)
        self._timer.timeout.connect(self._flush)
        self._timer.start(100)

    def _subscribe(self, topic):
        import rospy
        from rosgraph_msgs.msg import Log
        if self._sub is not None:
            self._sub.unregister()
        self._topic = topic
        self._sub = rospy.Subscriber(topic, Log, self._callback)

    def _callback(self, log):
        if self._widget.pause_button.isChecked():
            return
        m = Message(log.msg, log.level, log.name, (log.header.stamp.secs, log.header.stamp.nsecs),
                    list(log.topics), '%s:%s:%d' % (log.file, log.function, log.line))
        with self._lock:
            self._queue.append(m)

    def _flush(self):
        with self._lock:
            queue, self._queue = self._queue, []
        if queue:
            self._core.add(queue)
            self._widget.refresh()

    def trigger_configuration(self):
        import rospy
        dialog = QDialog(self._widget)
        dialog.setWindowTitle('Console Configuration')
        form = QFormLayout(dialog)
        combo = QComboBox()
        combo.setEditable(True)
        try:
            topics = sorted(t for t, ty in rospy.get_published_topics() if ty == 'rosgraph_msgs/Log')
        except Exception:
            topics = []
        combo.addItems(topics or [self._topic])
        combo.setEditText(self._topic)
        spin = QSpinBox()
        spin.setRange(100, 100000)
        spin.setSingleStep(1000)
        spin.setValue(self._core.limit)
        form.addRow('Rosout Topic', combo)
        form.addRow('Buffer Size', spin)
        buttons = QDialogButtonBox(QDialogButtonBox.Ok | QDialogButtonBox.Cancel)
        buttons.accepted.connect(dialog.accept)
        buttons.rejected.connect(dialog.reject)
        form.addRow(buttons)
        if dialog.exec_() == QDialog.Accepted:
            self._core.set_limit(spin.value())
            if combo.currentText() != self._topic:
                self._subscribe(combo.currentText())
            self._widget.refresh()

    def save_settings(self, plugin_settings, instance_settings):
        w = self._widget
        instance_settings.set_value('settings_exist', True)
        instance_settings.set_value('paused', w.pause_button.isChecked())
        instance_settings.set_value('show_highlighted_only', w.show_highlighted_only_check_box.isChecked())
        instance_settings.set_value('message_limit', self._core.limit)
        instance_settings.set_value('exclude_filters', 'severity')
        instance_settings.set_value('exclude_filter_0/severities',
                                    repr(sorted(w.exclude_severity.severities)))
        instance_settings.set_value('highlight_filters', 'message')
        instance_settings.set_value('highlight_filter_0/text', w.highlight_line_edit.text())
        instance_settings.set_value('highlight_filter_0/regex', w.highlight_regex_check_box.isChecked())

    def restore_settings(self, plugin_settings, instance_settings):
        w = self._widget
        if instance_settings.value('settings_exist') not in [True, 'true']:
            return
        try:
            self._core.set_limit(int(instance_settings.value('message_limit', DEFAULT_LIMIT)))
            sev = eval(str(instance_settings.value('exclude_filter_0/severities', '[]')))
        except Exception:
            sev = []
        for s, cb in w.severity_boxes.items():
            cb.setChecked(s in sev)
        w.highlight_line_edit.setText(str(instance_settings.value('highlight_filter_0/text', '')))
        w.highlight_regex_check_box.setChecked(instance_settings.value('highlight_filter_0/regex') in [True, 'true'])
        w.show_highlighted_only_check_box.setChecked(instance_settings.value('show_highlighted_only') in [True, 'true'])
        w.pause_button.setChecked(instance_settings.value('paused') in [True, 'true'])

    def shutdown_plugin(self):
        self._timer.stop()
        if self._sub is not None:
            self._sub.unregister()
