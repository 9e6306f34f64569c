"""rqt_graph plugin `RosGraph` ("Node Graph"): nodes and topics from the master, drawn by graphviz."""

from python_qt_binding.QtCore import Qt
from python_qt_binding.QtGui import QIcon, QPainter
from python_qt_binding.QtWidgets import (QCheckBox, QComboBox, QFileDialog, QGraphicsScene,
                                         QHBoxLayout, QLabel, QLineEdit, QPushButton, QSpinBox,
                                         QVBoxLayout, QWidget)
from rqt_gui_py.plugin import Plugin

from rqt_graph import graph_model
from rqt_graph.graph_view import GraphView, draw

CHECKBOXES = [
    # widget name, label, option key, default
    ('actionlib_check_box', 'Actions', 'group_actions', True),
    ('group_tf_check_box', 'tf', 'group_tf', True),
    ('group_image_check_box', 'Images', 'group_images', True),
    ('dead_sinks_check_box', 'Dead sinks', 'hide_dead_sinks', True),
    ('leaf_topics_check_box', 'Leaf topics', 'hide_leaf_topics', True),
    ('quiet_check_box', 'Debug', 'quiet', True),
    ('hide_tf_nodes_check_box', 'tf', 'hide_tf_nodes', False),
    ('unreachable_check_box', 'Unreachable', 'hide_unreachable', True),
    ('hide_dynamic_reconfigure_check_box', 'Params', 'hide_dynamic_reconfigure', True),
    ('highlight_connections_check_box', 'Highlight', None, True),
    ('auto_fit_graph_check_box', 'Fit', None, True),
]


class RosGraphWidget(QWidget):
    """The widget; `data_source()` returns a snapshot (see graph_model)."""

    def __init__(self, data_source, parent=None):
        super(RosGraphWidget, self).__init__(parent)
        self.setObjectName('RosGraphUi')
        self.setWindowTitle('Node Graph')
        self._data_source = data_source
        self._restored = False
        self.model = None
        self.dot = None
        self.node_items = {}
        self.edge_items = []
        self.error = None
        self._create_controls()
        self._lay_out()
        self._connect()
        self._snapshot = None

    def _create_controls(self):
        self.refresh_graph_push_button = QPushButton(QIcon.fromTheme('view-refresh'), 'Refresh')
        self.refresh_graph_push_button.setToolTip('Refresh ROS graph')
        self.refresh_graph_push_button.setObjectName('refresh_graph_push_button')
        self.graph_type_combo_box = QComboBox()
        self.graph_type_combo_box.setObjectName('graph_type_combo_box')
        for label, key in graph_model.GRAPH_TYPES:
            self.graph_type_combo_box.addItem(label, key)
        self.filter_line_edit = QLineEdit('/')
        self.filter_line_edit.setMinimumWidth(80)
        self.filter_line_edit.setObjectName('filter_line_edit')
        self.filter_line_edit.setToolTip('node/namespace filter (comma separated, -name excludes)')
        self.topic_filter_line_edit = QLineEdit('/')
        self.topic_filter_line_edit.setObjectName('topic_filter_line_edit')
        self.topic_filter_line_edit.setToolTip('topic filter (comma separated, -name excludes)')
        self.namespace_cluster_spin_box = QSpinBox()
        self.namespace_cluster_spin_box.setObjectName('namespace_cluster_spin_box')
        self.namespace_cluster_spin_box.setRange(0, 10)
        self.namespace_cluster_spin_box.setValue(2)
        self.fit_in_view_push_button = QPushButton(QIcon.fromTheme('zoom-original'), 'Fit')
        self.fit_in_view_push_button.setToolTip('Fit in view')
        self.save_dot_push_button = QPushButton('DOT')
        self.save_svg_push_button = QPushButton('SVG')
        self.save_image_push_button = QPushButton('Image')
        self.checkboxes = {}
        for name, label, _key, default in CHECKBOXES:
            cb = QCheckBox(label)
            cb.setObjectName(name)
            cb.setChecked(default)
            self.checkboxes[name] = cb
            setattr(self, name, cb)

    def _lay_out(self):
        row1 = QHBoxLayout()
        for w in (self.refresh_graph_push_button, self.graph_type_combo_box, self.filter_line_edit,
                  self.topic_filter_line_edit, self.fit_in_view_push_button, self.save_dot_push_button,
                  self.save_svg_push_button, self.save_image_push_button):
            row1.addWidget(w)
        row2 = QHBoxLayout()
        row2.addWidget(QLabel('Group:'))
        row2.addWidget(self.namespace_cluster_spin_box)
        row2.addWidget(QLabel('Namespaces'))
        for name in ('actionlib_check_box', 'group_tf_check_box', 'group_image_check_box'):
            row2.addWidget(self.checkboxes[name])
        row2.addWidget(QLabel('Hide:'))
        for name in ('dead_sinks_check_box', 'leaf_topics_check_box', 'quiet_check_box',
                     'hide_tf_nodes_check_box', 'unreachable_check_box',
                     'hide_dynamic_reconfigure_check_box'):
            row2.addWidget(self.checkboxes[name])
        row2.addStretch(1)
        row2.addWidget(self.checkboxes['highlight_connections_check_box'])
        row2.addWidget(self.checkboxes['auto_fit_graph_check_box'])

        self.scene = QGraphicsScene(self)
        self.scene.setBackgroundBrush(Qt.white)
        self.graphics_view = GraphView(self.scene, self)
        self.graphics_view.setRenderHint(QPainter.Antialiasing)
        self.status = QLabel()
        layout = QVBoxLayout(self)
        layout.addLayout(row1)
        layout.addLayout(row2)
        layout.addWidget(self.graphics_view, 1)
        layout.addWidget(self.status)

    def _connect(self):
        self.refresh_graph_push_button.clicked.connect(self.refresh)
        self.graph_type_combo_box.currentIndexChanged.connect(self.redraw)
        self.filter_line_edit.editingFinished.connect(self.redraw)
        self.topic_filter_line_edit.editingFinished.connect(self.redraw)
        self.namespace_cluster_spin_box.valueChanged.connect(self.redraw)
        for name, _l, key, _d in CHECKBOXES:
            if key:
                self.checkboxes[name].toggled.connect(self.redraw)
        self.fit_in_view_push_button.clicked.connect(self.fit)
        self.save_dot_push_button.clicked.connect(self.save_dot)
        self.save_svg_push_button.clicked.connect(self.save_svg)
        self.save_image_push_button.clicked.connect(self.save_image)

    # ---- options --------------------------------------------------------------------------
    def options(self):
        o = {'graph_type': self.graph_type_combo_box.currentData(),
             'node_filter': self.filter_line_edit.text(),
             'topic_filter': self.topic_filter_line_edit.text(),
             'namespace_cluster': self.namespace_cluster_spin_box.value()}
        for name, _l, key, _d in CHECKBOXES:
            if key:
                o[key] = self.checkboxes[name].isChecked()
        return o

    def save_settings(self, s):
        s.set_value('graph_type_combo_box_index', self.graph_type_combo_box.currentIndex())
        s.set_value('filter_line_edit_text', self.filter_line_edit.text())
        s.set_value('topic_filter_line_edit_text', self.topic_filter_line_edit.text())
        s.set_value('namespace_cluster_spin_box_value', self.namespace_cluster_spin_box.value())
        for name in self.checkboxes:
            s.set_value(name + '_state', self.checkboxes[name].isChecked())

    def restore_settings(self, s):
        widgets = [self.graph_type_combo_box, self.filter_line_edit, self.topic_filter_line_edit,
                   self.namespace_cluster_spin_box] + list(self.checkboxes.values())
        for w in widgets:
            w.blockSignals(True)
        try:
            self.graph_type_combo_box.setCurrentIndex(int(s.value('graph_type_combo_box_index', 0)))
            self.filter_line_edit.setText(str(s.value('filter_line_edit_text', '/')))
            self.topic_filter_line_edit.setText(str(s.value('topic_filter_line_edit_text', '/')))
            self.namespace_cluster_spin_box.setValue(int(s.value('namespace_cluster_spin_box_value', 2)))
            for name, _l, _k, default in CHECKBOXES:
                self.checkboxes[name].setChecked(s.value(name + '_state', default) in [True, 'true'])
        finally:
            for w in widgets:
                w.blockSignals(False)
        self._restored = True
        self.refresh()

    # ---- graph ----------------------------------------------------------------------------
    def refresh(self):
        try:
            self._snapshot = self._data_source()
        except Exception as e:
            self._show_error('could not get the graph from the master: %s' % e)
            return
        self.redraw()

    def redraw(self, *_):
        if not self._restored:
            return
        if self._snapshot is None:
            self.refresh()
            return
        self.model = graph_model.build(self._snapshot, self.options())
        self.dot = graph_model.dot_code(self.model, self.namespace_cluster_spin_box.value())
        try:
            plain = graph_model.layout(self.dot)
        except RuntimeError as e:
            self._show_error(str(e))
            return
        tooltips = {}
        colors = {}
        for n in self.model.nodes:
            tooltips['n_' + n] = n if n not in self.model.bad_nodes else '%s (%s)' % (n, self.model.bad_nodes[n])
            if n in self.model.bad_nodes:
                colors['n_' + n] = 'red' if self.model.bad_nodes[n] == 'DEAD' else 'orange'
        for t in self.model.topics:
            tooltips['t_' + t] = 'topic:' + t
        self.node_items, self.edge_items = draw(self.scene, plain, tooltips, colors)
        self.error = None
        self.status.setText('%d nodes, %d topics, %d edges' % (
            len(self.model.nodes), len(self.model.topics), len(self.model.edges)))
        if self.auto_fit_graph_check_box.isChecked():
            self.fit()

    def _show_error(self, text):
        self.error = text
        self.status.setText('ERROR: ' + text)
        import sys
        print('rqt_graph: %s' % text, file=sys.stderr, flush=True)

    def fit(self):
        self.graphics_view.fitInView(self.scene.itemsBoundingRect(), Qt.KeepAspectRatio)

    def showEvent(self, event):
        super(RosGraphWidget, self).showEvent(event)
        if self.auto_fit_graph_check_box.isChecked():
            self.fit()

    def resizeEvent(self, event):
        super(RosGraphWidget, self).resizeEvent(event)
        if self.auto_fit_graph_check_box.isChecked():
            self.fit()

    def save_dot(self, path=None):
        path = path or QFileDialog.getSaveFileName(self, 'Save as DOT', 'rosgraph.dot', 'DOT graph (*.dot)')[0]
        if path and self.dot:
            with open(path, 'w') as f:
                f.write(self.dot)

    def save_svg(self, path=None):
        from python_qt_binding.QtSvg import QSvgGenerator
        path = path or QFileDialog.getSaveFileName(self, 'Save as SVG', 'rosgraph.svg',
                                                   'Scalable Vector Graphic (*.svg)')[0]
        if not path:
            return
        gen = QSvgGenerator()
        gen.setFileName(path)
        size = self.scene.sceneRect().size().toSize() * 2
        gen.setSize(size)
        painter = QPainter(gen)
        painter.setRenderHint(QPainter.Antialiasing)
        self.scene.render(painter)
        painter.end()

    def save_image(self, path=None):
        from python_qt_binding.QtGui import QImage
        path = path or QFileDialog.getSaveFileName(self, 'Save as image', 'rosgraph.png',
                                                   'Image (*.bmp *.jpg *.png *.tiff)')[0]
        if not path:
            return
        img = QImage((self.scene.sceneRect().size() * 2).toSize(), QImage.Format_ARGB32_Premultiplied)
        img.fill(Qt.white)
        painter = QPainter(img)
        painter.setRenderHint(QPainter.Antialiasing)
        self.scene.render(painter)
        painter.end()
        img.save(path)


class RosGraph(Plugin):

    def __init__(self, context):
        super(RosGraph, self).__init__(context)
        self.setObjectName('RosGraph')
        from rqt_graph.ros_graph_data import RosGraphData
        self._data = RosGraphData()
        self._widget = RosGraphWidget(self._data.snapshot)
        if context.serial_number() > 1:
            self._widget.setWindowTitle(self._widget.windowTitle() + (' (%d)' % context.serial_number()))
        context.add_widget(self._widget)

    def save_settings(self, plugin_settings, instance_settings):
        self._widget.save_settings(instance_settings)

    def restore_settings(self, plugin_settings, instance_settings):
        self._widget.restore_settings(instance_settings)

    def shutdown_plugin(self):
        pass
