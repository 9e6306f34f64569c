"""rqt_tf_tree plugin `RosTfTree` ("TF Tree"): the tf2 frame tree drawn by graphviz."""
from python_qt_binding.QtCore import Qt, QTimer
from python_qt_binding.QtGui import QPainter
from python_qt_binding.QtWidgets import (QCheckBox, QGraphicsScene, QHBoxLayout, QLabel,
                                         QPushButton, QVBoxLayout, QWidget)
from rqt_graph import graph_model
from rqt_graph.graph_view import GraphView, draw
from rqt_gui_py.plugin import Plugin

from rqt_tf_tree.tf_tree_model import dot_code, parse_frames


class RosTfTree(Plugin):

    def __init__(self, context):
        super(RosTfTree, self).__init__(context)
        self.setObjectName('RosTfTree')
        import tf2_ros
        self._buffer = tf2_ros.Buffer()
        self._listener = tf2_ros.TransformListener(self._buffer)
        self._widget = w = QWidget()
        w.setObjectName('RosTfTreeUi')
        w.setWindowTitle('TF Tree')
        if context.serial_number() > 1:
            w.setWindowTitle(w.windowTitle() + (' (%d)' % context.serial_number()))
        self.clear_buffer_push_button = QPushButton('Clear TF Buffer')
        self.refresh_graph_push_button = QPushButton('Refresh TF Tree')
        self.highlight_connections_check_box = QCheckBox('Highlight')
        self.highlight_connections_check_box.setChecked(True)
        self.auto_fit_graph_check_box = QCheckBox('Fit')
        self.auto_fit_graph_check_box.setChecked(True)
        self.fit_in_view_push_button = QPushButton('Fit in view')
        bar = QHBoxLayout()
        for b in (self.clear_buffer_push_button, self.refresh_graph_push_button,
                  self.highlight_connections_check_box, self.auto_fit_graph_check_box,
                  self.fit_in_view_push_button):
            bar.addWidget(b)
        bar.addStretch(1)
        self.scene = QGraphicsScene(w)
        self.scene.setBackgroundBrush(Qt.white)
        self.graphics_view = GraphView(self.scene, w)
        self.graphics_view.setRenderHint(QPainter.Antialiasing)
        self.status = QLabel()
        layout = QVBoxLayout(w)
        layout.addLayout(bar)
        layout.addWidget(self.graphics_view, 1)
        layout.addWidget(self.status)
        self.frames = {}
        self.node_items = {}
        self.clear_buffer_push_button.clicked.connect(self._clear)
        self.refresh_graph_push_button.clicked.connect(self.refresh)
        self.fit_in_view_push_button.clicked.connect(self.fit)
        context.add_widget(w)
        # first generation after 1 s of collecting transforms, as the original
        QTimer.singleShot(1000, self.refresh)

    def _clear(self):
        self._buffer.clear()

    def refresh(self):
        import rospy
        self.frames = parse_frames(self._buffer.all_frames_as_yaml())
        dot = dot_code(self.frames, now=rospy.get_time())
        try:
            plain = graph_model.layout(dot)
        except RuntimeError as e:
            self.status.setText('ERROR: %s' % e)
            return
        self.node_items, _ = draw(self.scene, plain)
        self.status.setText('%d frames' % len(self.frames))
        if self.auto_fit_graph_check_box.isChecked():
            self.fit()

    def fit(self):
        self.graphics_view.fitInView(self.scene.itemsBoundingRect(), Qt.KeepAspectRatio)

    def save_settings(self, plugin_settings, instance_settings):
        instance_settings.set_value('auto_fit_graph_check_box_state', self.auto_fit_graph_check_box.isChecked())
        instance_settings.set_value('highlight_connections_check_box_state',
                                    self.highlight_connections_check_box.isChecked())

    def restore_settings(self, plugin_settings, instance_settings):
        self.auto_fit_graph_check_box.setChecked(
            instance_settings.value('auto_fit_graph_check_box_state', True) in [True, 'true'])
        self.highlight_connections_check_box.setChecked(
            instance_settings.value('highlight_connections_check_box_state', True) in [True, 'true'])

    def shutdown_plugin(self):
        try:
            self._listener.unregister()
        except Exception:
            pass
