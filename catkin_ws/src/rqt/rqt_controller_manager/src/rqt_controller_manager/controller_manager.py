"""rqt plugin ``ControllerManager``: pick a controller manager, see its controllers (and the
configured ones not loaded), load / start / stop / unload them from a context menu, and see a
controller's type and claimed resources on double-click. Refreshed once a second."""
import rospy
from controller_manager_msgs.srv import (LoadController, LoadControllerRequest, SwitchController,
                                         SwitchControllerRequest, UnloadController, UnloadControllerRequest)
from controller_manager_msgs.utils import (ControllerLister, ControllerManagerLister,
                                           get_rosparam_controller_names)
from python_qt_binding.QtCore import QAbstractTableModel, Qt, QTimer
from python_qt_binding.QtGui import QBrush, QColor, QCursor, QFont, QStandardItem, QStandardItemModel
from python_qt_binding.QtWidgets import (QComboBox, QFormLayout, QHBoxLayout, QHeaderView, QLabel, QMenu,
                                         QTableView, QTreeView, QVBoxLayout, QWidget)
from rqt_gui_py.plugin import Plugin

from rqt_controller_manager.model import (STATE_ICON, append_ns, menu_for, resolve_controllers_ns,
                                          resource_tree, table_rows)

LED = {'green': QColor(0, 170, 0), 'red': QColor(200, 0, 0), 'off': QColor(150, 150, 150)}


class ControllerTable(QAbstractTableModel):
    """Two columns: controller (bold, coloured by state) and state."""

    def __init__(self, rows, parent=None):
        super(ControllerTable, self).__init__(parent)
        self._rows = rows

    def rowCount(self, parent=None):
        return len(self._rows)

    def columnCount(self, parent=None):
        return 2

    def headerData(self, col, orientation, role):
        if orientation == Qt.Horizontal and role == Qt.DisplayRole:
            return ('controller', 'state')[col]
        return None

    def data(self, index, role):
        if not index.isValid():
            return None
        row = self._rows[index.row()]
        if role == Qt.DisplayRole:
            return row.name if index.column() == 0 else row.state
        if role == Qt.ForegroundRole and index.column() == 0:
            return QBrush(LED[STATE_ICON.get(row.state, 'off')])
        if role == Qt.FontRole and index.column() == 0:
            font = QFont()
            font.setBold(True)
            return font
        if role == Qt.TextAlignmentRole and index.column() == 1:
            return Qt.AlignCenter
        return None


class ControllerManagerWidget(QWidget):
    def __init__(self, parent=None):
        super(ControllerManagerWidget, self).__init__(parent)
        self.setObjectName('ControllerManagerUi')
        self.setWindowTitle('Controller Manager')
        self.cm_combo = QComboBox()
        self.cm_combo.setObjectName('cm_combo')
        self.table_view = QTableView()
        self.table_view.setObjectName('table_view')
        self.table_view.setSelectionBehavior(QTableView.SelectRows)
        self.table_view.verticalHeader().hide()
        top = QHBoxLayout()
        top.addWidget(QLabel('controller manager ns'))
        top.addWidget(self.cm_combo, 1)
        layout = QVBoxLayout(self)
        layout.addLayout(top)
        layout.addWidget(self.table_view, 1)


class ControllerInfoWidget(QWidget):
    def __init__(self, parent=None):
        super(ControllerInfoWidget, self).__init__(parent)
        self.setObjectName('ControllerInfoUi')
        self.setWindowTitle('Controller Info')
        self.ctrl_name = QLabel()
        self.ctrl_type = QLabel()
        self.resource_tree = QTreeView()
        self.resource_tree.setHeaderHidden(True)
        form = QFormLayout(self)
        form.addRow('Name', self.ctrl_name)
        form.addRow('Type', self.ctrl_type)
        form.addRow(self.resource_tree)


class ControllerManager(Plugin):
    _cm_update_freq = 1  # Hz

    def __init__(self, context):
        super(ControllerManager, self).__init__(context)
        self.setObjectName('ControllerManager')
        self._widget = ControllerManagerWidget()
        self._popup_widget = ControllerInfoWidget()
        if context.serial_number() > 1:
            self._widget.setWindowTitle(self._widget.windowTitle() + (' (%d)' % context.serial_number()))
        context.add_widget(self._widget)

        self._cm_ns = ''
        self._rows = []
        self._controller_lister = None
        self._load_srv = self._unload_srv = self._switch_srv = None
        self._list_cm = ControllerManagerLister()

        tv = self._widget.table_view
        tv.setContextMenuPolicy(Qt.CustomContextMenu)
        tv.customContextMenuRequested.connect(self._on_ctrl_menu)
        tv.doubleClicked.connect(self._on_ctrl_info)
        tv.horizontalHeader().setSectionResizeMode(QHeaderView.ResizeToContents)
        self._widget.cm_combo.currentTextChanged.connect(self._on_cm_change)

        self._timer = QTimer(self)
        self._timer.setInterval(int(1000 / self._cm_update_freq))
        self._timer.timeout.connect(self._refresh)
        self._timer.start()
        self._refresh()

    def shutdown_plugin(self):
        self._timer.stop()
        self._popup_widget.hide()

    def save_settings(self, plugin_settings, instance_settings):
        instance_settings.set_value('cm_ns', self._cm_ns)

    def restore_settings(self, plugin_settings, instance_settings):
        self._update_cm_list()
        cm_ns = instance_settings.value('cm_ns')
        idx = self._widget.cm_combo.findText(cm_ns) if cm_ns else -1
        if idx >= 0:
            self._widget.cm_combo.setCurrentIndex(idx)

    # -- refresh ---------------------------------------------------------------------------------
    def _refresh(self):
        self._update_cm_list()
        self._update_controllers()

    def _update_cm_list(self):
        combo = self._widget.cm_combo
        found = self._list_cm()
        current = [combo.itemText(i) for i in range(combo.count())]
        if found != current:
            selected = combo.currentText()
            combo.blockSignals(True)
            combo.clear()
            combo.addItems(found)
            combo.blockSignals(False)
            idx = combo.findText(selected)
            combo.setCurrentIndex(idx if idx >= 0 else (0 if found else -1))
            if combo.currentText() != self._cm_ns:
                self._on_cm_change(combo.currentText())

    def _on_cm_change(self, cm_ns):
        self._cm_ns = cm_ns or ''
        if self._cm_ns:
            self._load_srv = rospy.ServiceProxy(append_ns(cm_ns, 'load_controller'), LoadController)
            self._unload_srv = rospy.ServiceProxy(append_ns(cm_ns, 'unload_controller'), UnloadController)
            self._switch_srv = rospy.ServiceProxy(append_ns(cm_ns, 'switch_controller'), SwitchController)
            self._controller_lister = ControllerLister(cm_ns)
        else:
            self._load_srv = self._unload_srv = self._switch_srv = None
            self._controller_lister = None
        self._update_controllers()

    def _update_controllers(self):
        rows = self._list_controllers()
        if rows != self._rows or len(rows) != len(self._rows):
            self._rows = rows
            self._widget.table_view.setModel(ControllerTable(self._rows, self._widget.table_view))

    def _list_controllers(self):
        if not self._cm_ns or self._controller_lister is None:
            return []
        loaded = self._controller_lister()
        ctrls_ns = resolve_controllers_ns(self._cm_ns)
        configured = {}
        for name in get_rosparam_controller_names(ctrls_ns):
            try:
                configured[name] = rospy.get_param(append_ns(append_ns(ctrls_ns, name), 'type'))
            except (KeyError, rospy.ROSException):
                configured[name] = ''
        return table_rows(loaded, configured)

    # -- actions ---------------------------------------------------------------------------------
    def _on_ctrl_menu(self, pos):
        row = self._widget.table_view.rowAt(pos.y())
        if row < 0 or row >= len(self._rows):
            return
        ctrl = self._rows[row]
        menu = QMenu(self._widget.table_view)
        actions = [(menu.addAction(label), ops) for label, ops in menu_for(ctrl.state)]
        chosen = menu.exec_(self._widget.table_view.mapToGlobal(pos))
        for action, ops in actions:
            if action is chosen:
                self.run_operations(ctrl.name, ops)

    def run_operations(self, name, operations):
        """Run 'load' / 'start' / 'stop' / 'unload' on controller ``name`` in order."""
        try:
            for op in operations:
                if op == 'load':
                    self._load_srv.call(LoadControllerRequest(name=name))
                elif op == 'unload':
                    self._unload_srv.call(UnloadControllerRequest(name=name))
                else:
                    start, stop = ([name], []) if op == 'start' else ([], [name])
                    self._switch_srv.call(SwitchControllerRequest(
                        start_controllers=start, stop_controllers=stop,
                        strictness=SwitchControllerRequest.STRICT, start_asap=False, timeout=0.0))
        except (rospy.ServiceException, rospy.ROSException) as exc:
            rospy.logerr('Controller Manager: %s of %s failed: %s', '/'.join(operations), name, exc)
        self._update_controllers()

    def _on_ctrl_info(self, index):
        ctrl = self._rows[index.row()]
        popup = self._popup_widget
        popup.ctrl_name.setText(ctrl.name)
        popup.ctrl_type.setText(ctrl.type)
        title, interfaces = resource_tree(ctrl)
        model = QStandardItemModel()
        root = QStandardItem(title)
        model.appendRow(root)
        for iface, resources in interfaces:
            item = QStandardItem(iface)
            root.appendRow(item)
            for res in resources:
                item.appendRow(QStandardItem(res))
        popup.resource_tree.setModel(model)
        popup.resource_tree.expandAll()
        popup.move(QCursor.pos())
        popup.show()
