"""rqt_publisher plugin `Publisher` ("Message Publisher"): publish messages with field expressions."""
import sys
import threading

from python_qt_binding.QtCore import Qt, QTimer, Signal
from python_qt_binding.QtGui import QIcon
from python_qt_binding.QtWidgets import (QAbstractItemView, QComboBox, QHBoxLayout, QLabel, QMenu,
                                         QPushButton, QShortcut, QTreeWidget, QTreeWidgetItem,
                                         QVBoxLayout, QWidget)
from rqt_gui_py.plugin import Plugin

from rqt_publisher.expression import field_paths, fill_message

COL_TOPIC, COL_TYPE, COL_RATE, COL_EXPR = range(4)
ROLE_PATH = Qt.UserRole
ROLE_ID = Qt.UserRole + 1


def get_message_class(type_name):
    """The message class of 'pkg/Type', or None (primitive types and unknown types)."""
    import roslib.message
    if '/' not in type_name:
        return None
    try:
        return roslib.message.get_message_class(type_name)
    except Exception:
        return None


def all_message_types():
    import rosmsg
    import rospkg
    rp = rospkg.RosPack()
    out = []
    for pkg in sorted(rp.list()):
        try:
            out.extend(rosmsg.list_msgs(pkg, rospack=rp))
        except Exception:
            pass
    return sorted(set(out))


class PublisherWidget(QWidget):
    refreshed = Signal(object, object)

    def __init__(self, parent=None):
        super(PublisherWidget, self).__init__(parent)
        self.setObjectName('PublisherUi')
        self.setWindowTitle('Message Publisher')
        self.refresh_button = QPushButton(QIcon.fromTheme('view-refresh'), 'Refresh')
        self.refresh_button.setToolTip('Refresh topics and types')
        self.topic_combo_box = QComboBox()
        self.topic_combo_box.setObjectName('topic_combo_box')
        self.topic_combo_box.setEditable(True)
        self.topic_combo_box.setMinimumWidth(160)
        self.type_combo_box = QComboBox()
        self.type_combo_box.setObjectName('type_combo_box')
        self.type_combo_box.setEditable(True)
        self.type_combo_box.setMinimumWidth(180)
        self.frequency_combo_box = QComboBox()
        self.frequency_combo_box.setObjectName('frequency_combo_box')
        self.frequency_combo_box.setEditable(True)
        self.frequency_combo_box.addItem('1')
        self.frequency_combo_box.setToolTip('Frequency for periodic publishers in Hz (set to 0 for manual publishing)')
        self.add_publisher_button = QPushButton(QIcon.fromTheme('list-add'), '+')
        self.add_publisher_button.setObjectName('add_publisher_button')
        self.remove_publisher_button = QPushButton(QIcon.fromTheme('list-remove'), '-')
        self.clear_button = QPushButton(QIcon.fromTheme('edit-clear'), 'Clear')
        bar = QHBoxLayout()
        bar.addWidget(self.refresh_button)
        bar.addWidget(QLabel('Topic'))
        bar.addWidget(self.topic_combo_box, 2)
        bar.addWidget(QLabel('Type'))
        bar.addWidget(self.type_combo_box, 2)
        bar.addWidget(QLabel('Freq.'))
        bar.addWidget(self.frequency_combo_box)
        bar.addWidget(QLabel('Hz'))
        for w in (self.add_publisher_button, self.remove_publisher_button, self.clear_button):
            bar.addWidget(w)
        self.publisher_tree_widget = QTreeWidget()
        self.publisher_tree_widget.setObjectName('publisher_tree_widget')
        self.publisher_tree_widget.setHeaderLabels(['topic', 'type', 'rate', 'expression'])
        self.publisher_tree_widget.setSelectionMode(QAbstractItemView.ExtendedSelection)
        self.publisher_tree_widget.setContextMenuPolicy(Qt.CustomContextMenu)
        self.publisher_tree_widget.setColumnWidth(0, 220)
        self.publisher_tree_widget.setColumnWidth(1, 180)
        self.status = QLabel()
        self.status.setObjectName('status_label')
        layout = QVBoxLayout(self)
        layout.addLayout(bar)
        layout.addWidget(self.publisher_tree_widget, 1)
        layout.addWidget(self.status)
        self._topics = {}
        self.refresh_button.clicked.connect(self.refresh_combo_boxes)
        self.topic_combo_box.currentIndexChanged.connect(self._topic_chosen)
        self.refreshed.connect(self._fill)

    def refresh_combo_boxes(self):
        self.type_combo_box.setEnabled(False)
        self.topic_combo_box.setEnabled(False)
        self.type_combo_box.setEditText('updating...')
        self.topic_combo_box.setEditText('updating...')

        def work():
            try:
                import rospy
                topics = dict(rospy.get_published_topics())
            except Exception:
                topics = {}
            types = all_message_types()
            self.refreshed.emit(topics, types)
        threading.Thread(target=work, daemon=True).start()

    def _fill(self, topics, types):
        self._topics = topics
        self.type_combo_box.clear()
        self.type_combo_box.addItems(types)
        self.topic_combo_box.clear()
        self.topic_combo_box.addItems(sorted(topics))
        self.type_combo_box.setEnabled(True)
        self.topic_combo_box.setEnabled(True)

    def _topic_chosen(self, _index):
        t = self._topics.get(self.topic_combo_box.currentText())
        if t:
            self.type_combo_box.setEditText(t)


class Publisher(Plugin):

    def __init__(self, context):
        super(Publisher, self).__init__(context)
        self.setObjectName('Publisher')
        self._widget = PublisherWidget()
        if context.serial_number() > 1:
            self._widget.setWindowTitle(self._widget.windowTitle() + (' (%d)' % context.serial_number()))
        self._publishers = {}
        self._id_counter = 0
        self._updating = False
        w = self._widget
        w.add_publisher_button.clicked.connect(self._add_from_bar)
        w.remove_publisher_button.clicked.connect(self.remove_selected)
        w.clear_button.clicked.connect(self.clean_up_publishers)
        w.publisher_tree_widget.itemChanged.connect(self._item_changed)
        w.publisher_tree_widget.customContextMenuRequested.connect(self._context_menu)
        QShortcut(Qt.Key_Delete, w.publisher_tree_widget, self.remove_selected)
        context.add_widget(w)
        w.refresh_combo_boxes()

    # ---- publishers ---------------------------------------------------------------------
    def _add_from_bar(self):
        w = self._widget
        try:
            rate = float(w.frequency_combo_box.currentText())
        except ValueError:
            self._report('invalid frequency "%s"' % w.frequency_combo_box.currentText())
            return
        self.add_publisher(w.topic_combo_box.currentText().strip(), w.type_combo_box.currentText().strip(),
                           rate, False)

    def add_publisher(self, topic_name, type_name, rate, enabled, expressions=None, counter=0):
        """Add a publisher row; its id, or None with one status line when the input is bad."""
        import rospy
        if not topic_name or not topic_name.lstrip('/'):
            self._report('Publisher.add_publisher(): empty topic name')
            return None
        cls = get_message_class(type_name)
        if cls is None:
            self._report('Publisher.add_publisher(): could not find type "%s" for topic "%s"'
                         % (type_name, topic_name))
            return None
        pid = self._id_counter
        self._id_counter += 1
        info = {'topic_name': str(topic_name), 'type_name': str(type_name), 'rate': float(rate),
                'enabled': bool(enabled), 'publisher_id': pid, 'counter': int(counter),
                'expressions': dict(expressions or {}), 'message_class': cls, 'timer': QTimer(self)}
        info['publisher'] = rospy.Publisher(info['topic_name'], cls, queue_size=100)
        info['timer'].timeout.connect(lambda pid=pid: self.publish_once(pid))
        self._publishers[pid] = info
        self._add_rows(info)
        self._update_timer(info)
        return pid

    def _add_rows(self, info):
        tree = self._widget.publisher_tree_widget
        self._updating = True
        try:
            top = QTreeWidgetItem([info['topic_name'], info['type_name'], '%.2f' % info['rate'], ''])
            top.setData(0, ROLE_ID, info['publisher_id'])
            top.setData(0, ROLE_PATH, '')
            top.setFlags(top.flags() | Qt.ItemIsUserCheckable | Qt.ItemIsEditable)
            top.setCheckState(0, Qt.Checked if info['enabled'] else Qt.Unchecked)
            tree.addTopLevelItem(top)
            items = {'': top}
            for path, slot_type in field_paths(info['message_class'], '', get_message_class):
                parent = items[path.rsplit('/', 1)[0]]
                name = path.rsplit('/', 1)[1]
                item = QTreeWidgetItem(parent, [name, slot_type, '', info['expressions'].get(path, '')])
                item.setData(0, ROLE_ID, info['publisher_id'])
                item.setData(0, ROLE_PATH, path)
                item.setFlags(item.flags() | Qt.ItemIsEditable)
                if slot_type == 'bool':
                    item.setFlags(item.flags() | Qt.ItemIsUserCheckable)
                    item.setCheckState(COL_EXPR, Qt.Checked if info['expressions'].get(path) == 'True'
                                       else Qt.Unchecked)
                items[path] = item
            top.setExpanded(True)
            info['items'] = items
        finally:
            self._updating = False

    def _item_changed(self, item, column):
        if self._updating:
            return
        pid = item.data(0, ROLE_ID)
        info = self._publishers.get(pid)
        if info is None:
            return
        path = item.data(0, ROLE_PATH)
        self._updating = True
        try:
            if path == '':
                if column == COL_TOPIC:
                    info['enabled'] = item.checkState(0) == Qt.Checked
                    self._update_timer(info)
                elif column == COL_RATE:
                    try:
                        info['rate'] = float(item.text(COL_RATE))
                    except ValueError:
                        self._report('invalid rate "%s" for topic "%s"' % (item.text(COL_RATE), info['topic_name']))
                    item.setText(COL_RATE, '%.2f' % info['rate'])
                    self._update_timer(info)
            elif column == COL_EXPR:
                if item.text(1) == 'bool' and item.flags() & Qt.ItemIsUserCheckable:
                    text = 'True' if item.checkState(COL_EXPR) == Qt.Checked else 'False'
                    if item.text(COL_EXPR) not in ('', 'True', 'False'):
                        text = item.text(COL_EXPR)
                    item.setText(COL_EXPR, text)
                self.set_expression(pid, path, item.text(COL_EXPR))
        finally:
            self._updating = False

    def set_expression(self, pid, path, text):
        info = self._publishers[pid]
        text = text.split(' # error', 1)[0]
        if text.strip():
            info['expressions'][path] = text
        else:
            info['expressions'].pop(path, None)
        item = info.get('items', {}).get(path)
        if item is not None and item.text(COL_EXPR) != text:
            was, self._updating = self._updating, True
            item.setText(COL_EXPR, text)
            self._updating = was
        # check the expression now (with the next counter value) so a bad one is shown at once
        _msg, errors = fill_message(info['message_class'], {path: text} if text.strip() else {},
                                    info['counter'] + 1, get_message_class)
        if path in errors:
            self._show_error(info, path, errors[path])

    def set_enabled(self, pid, enabled):
        info = self._publishers[pid]
        info['items'][''].setCheckState(0, Qt.Checked if enabled else Qt.Unchecked)

    def _update_timer(self, info):
        info['timer'].stop()
        if info['enabled'] and info['rate'] > 0:
            info['timer'].start(int(1000 / info['rate']))

    def publish_once(self, pid):
        info = self._publishers.get(pid)
        if info is None:
            return
        info['counter'] += 1
        msg, errors = fill_message(info['message_class'], info['expressions'], info['counter'],
                                   get_message_class)
        for path, text in errors.items():
            self._show_error(info, path, text)
        try:
            info['publisher'].publish(msg)
        except Exception as e:
            self._report('could not publish on "%s": %s' % (info['topic_name'], e))

    def _show_error(self, info, path, text):
        item = info.get('items', {}).get(path)
        if item is not None and item.text(COL_EXPR) != text:
            was, self._updating = self._updating, True
            item.setText(COL_EXPR, text)
            self._updating = was
        self._report('%s%s: %s' % (info['topic_name'], path, text))

    def _report(self, line):
        if self._widget.status.text() != line:
            self._widget.status.setText(line)
            print('rqt_publisher: %s' % line, file=sys.stderr, flush=True)

    def remove_publisher(self, pid):
        info = self._publishers.pop(pid, None)
        if info is None:
            return
        info['timer'].stop()
        info['publisher'].unregister()
        tree = self._widget.publisher_tree_widget
        top = info['items']['']
        tree.takeTopLevelItem(tree.indexOfTopLevelItem(top))

    def remove_selected(self):
        for pid in {i.data(0, ROLE_ID) for i in self._widget.publisher_tree_widget.selectedItems()}:
            self.remove_publisher(pid)

    def clean_up_publishers(self):
        for pid in list(self._publishers):
            self.remove_publisher(pid)

    def _context_menu(self, pos):
        menu = QMenu(self._widget)
        once = menu.addAction('Publish Selected Once')
        remove = menu.addAction('Remove Selected')
        menu.addSeparator()
        expand = menu.addAction('Expand All')
        collapse = menu.addAction('Collapse All')
        chosen = menu.exec_(self._widget.publisher_tree_widget.mapToGlobal(pos))
        if chosen is once:
            for pid in {i.data(0, ROLE_ID) for i in self._widget.publisher_tree_widget.selectedItems()}:
                self.publish_once(pid)
        elif chosen is remove:
            self.remove_selected()
        elif chosen is expand:
            self._widget.publisher_tree_widget.expandAll()
        elif chosen is collapse:
            self._widget.publisher_tree_widget.collapseAll()

    # ---- plugin API -----------------------------------------------------------------------
    def save_settings(self, plugin_settings, instance_settings):
        pubs = []
        for pid in sorted(self._publishers):
            info = self._publishers[pid]
            pubs.append({'topic_name': info['topic_name'], 'type_name': info['type_name'],
                         'rate': info['rate'], 'enabled': False, 'publisher_id': pid,
                         'counter': info['counter'], 'expressions': dict(info['expressions'])})
        instance_settings.set_value('publishers', repr(pubs))

    def restore_settings(self, plugin_settings, instance_settings):
        text = instance_settings.value('publishers')
        if not text:
            return
        try:
            pubs = eval(str(text))
        except Exception as e:
            self._report('could not restore the saved publishers: %s' % e)
            return
        for p in pubs:
            self.add_publisher(p.get('topic_name', ''), p.get('type_name', ''), p.get('rate', 1.0), False,
                               p.get('expressions'), p.get('counter', 0))

    def shutdown_plugin(self):
        self.clean_up_publishers()
