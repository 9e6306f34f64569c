"""rqt_topic plugin ("Topic Monitor"): type, bandwidth, rate and last value of topics."""
import threading

from python_qt_binding.QtCore import Qt, QTimer
from python_qt_binding.QtWidgets import (QHeaderView, QMenu, QTreeWidget, QTreeWidgetItem,
                                         QVBoxLayout, QWidget)
from rqt_gui_py.plugin import Plugin

from rqt_topic.topic_stats import TopicStats, format_bandwidth, format_hz, value_rows

COLUMNS = ['Topic', 'Type', 'Bandwidth', 'Hz', 'Value']


class SortItem(QTreeWidgetItem):
    def __lt__(self, other):
        col = self.treeWidget().sortColumn() if self.treeWidget() else 0
        if col == 2:
            return (self.data(2, Qt.UserRole) or 0.0) < (other.data(2, Qt.UserRole) or 0.0)
        return self.text(col) < other.text(col)


class TopicWidget(QWidget):

    def __init__(self, parent=None):
        super(TopicWidget, self).__init__(parent)
        self.setObjectName('TopicWidgetUi')
        self.setWindowTitle('Topic Monitor')
        self.topics_tree_widget = QTreeWidget()
        self.topics_tree_widget.setObjectName('topics_tree_widget')
        self.topics_tree_widget.setHeaderLabels(COLUMNS)
        self.topics_tree_widget.setSortingEnabled(True)
        self.topics_tree_widget.sortByColumn(0, Qt.AscendingOrder)
        self.topics_tree_widget.setColumnWidth(0, 220)
        self.topics_tree_widget.setColumnWidth(1, 180)
        self.topics_tree_widget.setContextMenuPolicy(Qt.CustomContextMenu)
        self.topics_tree_widget.header().setContextMenuPolicy(Qt.CustomContextMenu)
        layout = QVBoxLayout(self)
        layout.addWidget(self.topics_tree_widget)
        self.items = {}        # topic -> top-level item
        self.stats = {}        # topic -> TopicStats (monitored)
        self.subs = {}
        self.errors = {}
        self._lock = threading.Lock()
        self._updating = False
        self.topics_tree_widget.itemChanged.connect(self._changed)
        self.topics_tree_widget.customContextMenuRequested.connect(self._menu)
        self.topics_tree_widget.header().customContextMenuRequested.connect(self._header_menu)
        self._timer = QTimer(self)
        self._timer.timeout.connect(self.refresh)
        self._timer.start(1000)

    def refresh(self):
        import rospy
        try:
            topics = dict(rospy.get_published_topics())
        except Exception:
            return
        self._updating = True
        try:
            for topic, type_name in topics.items():
                if topic not in self.items:
                    item = SortItem([topic, type_name, '', '', 'not monitored'])
                    item.setFlags(item.flags() | Qt.ItemIsUserCheckable)
                    item.setCheckState(0, Qt.Unchecked)
                    self.topics_tree_widget.addTopLevelItem(item)
                    self.items[topic] = item
            for topic in list(self.items):
                if topic not in topics and topic not in self.stats:
                    item = self.items.pop(topic)
                    self.topics_tree_widget.takeTopLevelItem(self.topics_tree_widget.indexOfTopLevelItem(item))
            now = rospy.get_time()
            for topic, stats in list(self.stats.items()):
                self._show(topic, stats, now)
        finally:
            self._updating = False

    def _show(self, topic, stats, now):
        item = self.items[topic]
        with self._lock:
            hz = stats.hz()
            bw = stats.bandwidth(now)
            msg = stats.last_message
        item.setText(2, format_bandwidth(bw))
        item.setData(2, Qt.UserRole, bw or 0.0)
        item.setText(3, format_hz(hz))
        if msg is None:
            return
        rows = value_rows(msg)
        existing = {item.child(i).text(0): item.child(i) for i in range(item.childCount())}
        keep = set()
        for path, text in rows:
            child = existing.get(path)
            if child is None:
                child = SortItem(item, [path, '', '', '', text])
            else:
                child.setText(4, text)
            keep.add(path)
        for path, child in existing.items():
            if path not in keep:
                item.removeChild(child)

    def _changed(self, item, column):
        if self._updating or column != 0 or item.parent() is not None:
            return
        topic = item.text(0)
        if item.checkState(0) == Qt.Checked:
            self.start_monitoring(topic)
        else:
            self.stop_monitoring(topic)

    def start_monitoring(self, topic):
        import roslib.message
        import rospy
        item = self.items.get(topic)
        type_name = item.text(1) if item else None
        cls = None
        try:
            cls = roslib.message.get_message_class(type_name)
        except Exception:
            cls = None
        if cls is None:
            text = 'can not get message class for type "%s"' % type_name
            self.errors[topic] = text
            if item:
                item.setText(4, text)
            return False
        stats = TopicStats()
        self.stats[topic] = stats
        if item:
            item.setText(4, '')

        def cb(msg, topic=topic):
            import io
            buf = io.BytesIO()
            try:
                msg.serialize(buf)
                size = buf.tell()
            except Exception:
                size = 0
            with self._lock:
                stats.add(rospy.get_time(), size, msg)
        self.subs[topic] = rospy.Subscriber(topic, cls, cb)
        return True

    def stop_monitoring(self, topic):
        sub = self.subs.pop(topic, None)
        if sub:
            sub.unregister()
        self.stats.pop(topic, None)
        item = self.items.get(topic)
        if item:
            item.takeChildren()
            for c in (2, 3):
                item.setText(c, '')
            item.setText(4, 'not monitored')

    def set_monitored(self, topic, on=True):
        item = self.items[topic]
        item.setCheckState(0, Qt.Checked if on else Qt.Unchecked)

    def _menu(self, pos):
        item = self.topics_tree_widget.itemAt(pos)
        if item is None:
            return
        menu = QMenu(self)
        expand = menu.addAction('Expand All Children')
        collapse = menu.addAction('Collapse All Children')
        chosen = menu.exec_(self.topics_tree_widget.mapToGlobal(pos))
        if chosen in (expand, collapse):
            stack = [item]
            while stack:
                it = stack.pop()
                it.setExpanded(chosen is expand)
                stack.extend(it.child(i) for i in range(it.childCount()))

    def _header_menu(self, pos):
        menu = QMenu(self)
        toggle = menu.addAction('Toggle Auto-Resize')
        if menu.exec_(self.topics_tree_widget.header().mapToGlobal(pos)) is toggle:
            header = self.topics_tree_widget.header()
            mode = header.sectionResizeMode(0)
            header.setSectionResizeMode(QHeaderView.Interactive if mode == QHeaderView.ResizeToContents
                                        else QHeaderView.ResizeToContents)

    def shutdown(self):
        self._timer.stop()
        for topic in list(self.subs):
            self.stop_monitoring(topic)


class Topic(Plugin):

    def __init__(self, context):
        super(Topic, self).__init__(context)
        self.setObjectName('Topic')
        self._widget = TopicWidget()
        if context.serial_number() > 1:
            self._widget.setWindowTitle(self._widget.windowTitle() + (' (%d)' % context.serial_number()))
        context.add_widget(self._widget)
        self._widget.refresh()

    def save_settings(self, plugin_settings, instance_settings):
        instance_settings.set_value('tree_widget_header_state',
                                    self._widget.topics_tree_widget.header().saveState())

    def restore_settings(self, plugin_settings, instance_settings):
        state = instance_settings.value('tree_widget_header_state')
        if state is not None:
            try:
                self._widget.topics_tree_widget.header().restoreState(state)
            except TypeError:
                pass

    def shutdown_plugin(self):
        self._widget.shutdown()


TopicPlugin = Topic
