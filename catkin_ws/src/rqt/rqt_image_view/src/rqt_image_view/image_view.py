"""rqt_image_view plugin `ImageView` ("Image View"): shows sensor_msgs/Image (raw or compressed)."""
import sys

from python_qt_binding.QtCore import QRectF, Qt, Signal
from python_qt_binding.QtGui import QColor, QImage, QPainter, QPen
from python_qt_binding.QtWidgets import (QCheckBox, QComboBox, QDoubleSpinBox, QFileDialog,
                                         QHBoxLayout, QLabel, QLineEdit, QPushButton, QSpinBox,
                                         QVBoxLayout, QWidget)
from rqt_gui_py.plugin import Plugin

from rqt_image_view.image_convert import (COLOR_SCHEMES, ConversionError, click_to_image,
                                          decode_compressed, image_to_rgb, rotate, topic_entries)


class ImageFrame(QWidget):
    clicked = Signal(int, int)

    def __init__(self, parent=None):
        super(ImageFrame, self).__init__(parent)
        self.setObjectName('image_frame')
        self.image = None          # QImage
        self.rgb = None            # displayed array (kept alive for QImage)
        self.smooth = False
        self.gridlines = 0
        self.setMinimumSize(80, 60)

    def set_rgb(self, rgb):
        self.rgb = rgb
        h, w = rgb.shape[:2]
        self.image = QImage(rgb.data, w, h, 3 * w, QImage.Format_RGB888)
        self.update()

    def _target(self):
        if self.image is None:
            return QRectF()
        w, h = self.image.width(), self.image.height()
        s = min(self.width() / float(w), self.height() / float(h))
        tw, th = w * s, h * s
        return QRectF((self.width() - tw) / 2, (self.height() - th) / 2, tw, th)

    def paintEvent(self, event):
        p = QPainter(self)
        p.fillRect(self.rect(), QColor('#d0d0d0'))
        if self.image is None:
            return
        if self.smooth:
            p.setRenderHint(QPainter.SmoothPixmapTransform)
        t = self._target()
        p.drawImage(t, self.image)
        if self.gridlines:
            p.setCompositionMode(QPainter.RasterOp_SourceXorDestination)
            p.setPen(QPen(QColor('white')))
            for k in range(1, self.gridlines + 1):
                x = t.left() + t.width() * k / (self.gridlines + 1)
                y = t.top() + t.height() * k / (self.gridlines + 1)
                p.drawLine(int(x), int(t.top()), int(x), int(t.bottom()))
                p.drawLine(int(t.left()), int(y), int(t.right()), int(y))

    def mousePressEvent(self, event):
        if event.button() != Qt.LeftButton or self.image is None:
            return
        t = self._target()
        if not t.contains(event.pos()):
            return
        x = int(round((event.pos().x() - t.left()) * self.image.width() / t.width() - 0.5))
        y = int(round((event.pos().y() - t.top()) * self.image.height() / t.height() - 0.5))
        self.clicked.emit(max(0, min(self.image.width() - 1, x)), max(0, min(self.image.height() - 1, y)))


class ImageView(Plugin):
    image_ready = Signal(object)

    def __init__(self, context):
        super(ImageView, self).__init__(context)
        self.setObjectName('ImageView')
        self._args = context.argv()
        self._widget = w = QWidget()
        w.setObjectName('ImageViewUi')
        w.setWindowTitle('Image View')
        if context.serial_number() > 1:
            w.setWindowTitle(w.windowTitle() + (' (%d)' % context.serial_number()))
        self.topics_combo_box = QComboBox()
        self.topics_combo_box.setObjectName('topics_combo_box')
        self.topics_combo_box.setMinimumWidth(220)
        self.refresh_topics_push_button = QPushButton('Refresh')
        self.zoom_1_push_button = QPushButton('1:1')
        self.zoom_1_push_button.setCheckable(True)
        self.dynamic_range_check_box = QCheckBox('Dynamic depth range')
        self.max_range_double_spin_box = QDoubleSpinBox()
        self.max_range_double_spin_box.setRange(0.01, 100.0)
        self.max_range_double_spin_box.setValue(10.0)
        self.color_scheme_combo_box = QComboBox()
        self.color_scheme_combo_box.addItems(COLOR_SCHEMES)
        self.num_gridlines_spin_box = QSpinBox()
        self.num_gridlines_spin_box.setRange(0, 20)
        self.save_as_image_push_button = QPushButton('Save')
        self.smooth_image_check_box = QCheckBox('Smooth scaling')
        self.rotate_left_push_button = QPushButton('<')
        self.rotate_label = QLabel('0°')
        self.rotate_right_push_button = QPushButton('>')
        self.publish_click_location_check_box = QCheckBox()
        self.publish_click_location_topic_line_edit = QLineEdit()
        self.status = QLabel()
        bar = QHBoxLayout()
        for x in (self.refresh_topics_push_button, self.topics_combo_box, self.zoom_1_push_button,
                  self.save_as_image_push_button, self.rotate_left_push_button, self.rotate_label,
                  self.rotate_right_push_button, self.publish_click_location_check_box,
                  self.publish_click_location_topic_line_edit):
            bar.addWidget(x)
        bar2 = QHBoxLayout()
        for x in (self.dynamic_range_check_box, QLabel('Max depth'), self.max_range_double_spin_box,
                  self.color_scheme_combo_box, QLabel('Grid'), self.num_gridlines_spin_box,
                  self.smooth_image_check_box):
            bar2.addWidget(x)
        bar2.addStretch(1)
        self.publish_click_location_check_box.setToolTip('publish the location of left clicks')
        self.image_frame = ImageFrame()
        layout = QVBoxLayout(w)
        layout.addLayout(bar)
        layout.addLayout(bar2)
        layout.addWidget(self.image_frame, 1)
        layout.addWidget(self.status)
        self._rotate = 0
        self._sub = None
        self._topic = ('', 'raw')
        self._mouse_pub = None
        self._mouse_topic = None
        self._raw = None            # last converted frame before rotation
        self._entries = []
        self.frames = 0
        self.refresh_topics_push_button.clicked.connect(self.update_topic_list)
        self.topics_combo_box.currentIndexChanged.connect(self._on_topic_index)
        self.smooth_image_check_box.toggled.connect(self._on_smooth)
        self.num_gridlines_spin_box.valueChanged.connect(self._on_grid)
        self.rotate_left_push_button.clicked.connect(lambda: self._set_rotate(self._rotate - 1))
        self.rotate_right_push_button.clicked.connect(lambda: self._set_rotate(self._rotate + 1))
        self.save_as_image_push_button.clicked.connect(lambda: self.save_image())
        self.publish_click_location_check_box.toggled.connect(self._update_mouse_pub)
        self.publish_click_location_topic_line_edit.editingFinished.connect(self._update_mouse_pub)
        self.image_frame.clicked.connect(self._on_click)
        self.image_ready.connect(self._show)
        context.add_widget(w)

    # ---- topics ---------------------------------------------------------------------------
    def update_topic_list(self, select=None):
        import rospy
        try:
            types = dict(rospy.get_published_topics())
        except Exception:
            types = {}
        self._entries = topic_entries(types)
        current = select or self._topic
        self.topics_combo_box.blockSignals(True)
        self.topics_combo_box.clear()
        index = 0
        for k, (display, key) in enumerate(self._entries):
            self.topics_combo_box.addItem(display)
            if key == tuple(current) or (display and display == current[0] and current[1] == 'raw'):
                index = k
        if select and index == 0 and select[0]:
            # a topic given on the command line that is not published yet: subscribe anyway
            self._entries.append((select[0], tuple(select)))
            self.topics_combo_box.addItem(select[0])
            index = len(self._entries) - 1
        self.topics_combo_box.setCurrentIndex(index)
        self.topics_combo_box.blockSignals(False)
        self._on_topic_index(index)

    def _on_topic_index(self, index):
        if 0 <= index < len(self._entries):
            self.subscribe(*self._entries[index][1])

    def subscribe(self, topic, transport='raw'):
        import rospy
        from sensor_msgs.msg import CompressedImage, Image
        if self._sub is not None:
            self._sub.unregister()
            self._sub = None
        self._topic = (topic, transport)
        self._update_mouse_pub()
        if not topic:
            return
        if transport == 'raw':
            self._sub = rospy.Subscriber(topic, Image, self._on_image, queue_size=1)
        elif transport in ('compressed', 'compressedDepth'):
            self._sub = rospy.Subscriber('%s/%s' % (topic, transport), CompressedImage,
                                         self._on_compressed, queue_size=1)
        else:
            self._report('Loading image transport plugin failed: transport "%s" is not supported' % transport)

    def _on_image(self, msg):
        try:
            rgb = image_to_rgb(msg.encoding, msg.height, msg.width, msg.step, msg.data,
                               bool(msg.is_bigendian), self.max_range_double_spin_box.value(),
                               self.dynamic_range_check_box.isChecked(),
                               self.color_scheme_combo_box.currentText())
        except ConversionError as e:
            self.image_ready.emit(str(e))
            return
        self.image_ready.emit(rgb)

    def _on_compressed(self, msg):
        try:
            self.image_ready.emit(decode_compressed(msg.data))
        except ConversionError as e:
            self.image_ready.emit(str(e))

    def _show(self, rgb):
        if isinstance(rgb, str):
            self._report(rgb)
            return
        self.frames += 1
        self._raw = rgb
        shown = rotate(rgb, self._rotate)
        self.image_frame.set_rgb(shown)
        if self.zoom_1_push_button.isChecked():
            self.image_frame.setFixedSize(shown.shape[1], shown.shape[0])
        else:
            self.image_frame.setMinimumSize(80, 60)
            self.image_frame.setMaximumSize(16777215, 16777215)

    def _report(self, line):
        if self.status.text() != line:
            self.status.setText(line)
            print('rqt_image_view: %s' % line, file=sys.stderr, flush=True)

    # ---- view options ---------------------------------------------------------------------
    def _on_smooth(self, on):
        self.image_frame.smooth = on
        self.image_frame.update()

    def _on_grid(self, n):
        self.image_frame.gridlines = n
        self.image_frame.update()

    def _set_rotate(self, r):
        self._rotate = r % 4
        self.rotate_label.setText('%d°' % (90 * self._rotate))
        if self._raw is not None:
            self._show(self._raw)

    def save_image(self, path=None):
        if self.image_frame.image is None:
            return
        path = path or QFileDialog.getSaveFileName(self._widget, 'Save as image', 'image.png',
                                                   'Image (*.bmp *.jpg *.png *.jpeg)')[0]
        if path:
            self.image_frame.image.save(path)

    # ---- mouse clicks ---------------------------------------------------------------------
    def _update_mouse_pub(self, *_):
        import rospy
        from geometry_msgs.msg import Point
        edit = self.publish_click_location_topic_line_edit
        if not edit.isModified() or not edit.text().strip():
            edit.setText('%s_mouse_left' % self._topic[0] if self._topic[0] else 'mouse_left')
        topic = edit.text().strip()
        if self.publish_click_location_check_box.isChecked():
            if self._mouse_topic != topic:
                if self._mouse_pub is not None:
                    self._mouse_pub.unregister()
                self._mouse_pub = rospy.Publisher(topic, Point, queue_size=1000)
                self._mouse_topic = topic
        elif self._mouse_pub is not None:
            self._mouse_pub.unregister()
            self._mouse_pub = None
            self._mouse_topic = None

    def _on_click(self, x, y):
        if self._mouse_pub is None or self._raw is None:
            return
        from geometry_msgs.msg import Point
        h, w = self._raw.shape[:2]
        ox, oy = click_to_image(x, y, w, h, self._rotate)
        self._mouse_pub.publish(Point(float(ox), float(oy), 0.0))

    # ---- plugin API -------------------------------------------------------------------------
    def save_settings(self, plugin_settings, instance_settings):
        s = instance_settings
        s.set_value('topic', '%s %s' % self._topic if self._topic[0] else '')
        s.set_value('zoom1', self.zoom_1_push_button.isChecked())
        s.set_value('dynamic_range', self.dynamic_range_check_box.isChecked())
        s.set_value('max_range', self.max_range_double_spin_box.value())
        s.set_value('publish_click_location', self.publish_click_location_check_box.isChecked())
        s.set_value('mouse_pub_topic', self.publish_click_location_topic_line_edit.text())
        s.set_value('toolbar_hidden', False)
        s.set_value('num_gridlines', self.num_gridlines_spin_box.value())
        s.set_value('smooth_image', self.smooth_image_check_box.isChecked())
        s.set_value('rotate', self._rotate)
        s.set_value('color_scheme', self.color_scheme_combo_box.currentIndex())

    def restore_settings(self, plugin_settings, instance_settings):
        s = instance_settings

        def t(k, d=False):
            return s.value(k, d) in [True, 'true']
        self.zoom_1_push_button.setChecked(t('zoom1'))
        self.dynamic_range_check_box.setChecked(t('dynamic_range'))
        try:
            self.max_range_double_spin_box.setValue(float(s.value('max_range', 10.0)))
            self.num_gridlines_spin_box.setValue(int(s.value('num_gridlines', 0)))
            self.color_scheme_combo_box.setCurrentIndex(int(s.value('color_scheme', 0)))
            self._set_rotate(int(s.value('rotate', 0)))
        except (TypeError, ValueError):
            pass
        self.smooth_image_check_box.setChecked(t('smooth_image'))
        mouse = str(s.value('mouse_pub_topic', '') or '')
        if mouse:
            self.publish_click_location_topic_line_edit.setText(mouse)
        self.publish_click_location_check_box.setChecked(t('publish_click_location'))
        saved = str(s.value('topic', '') or '').split(' ')
        select = (saved[0], saved[1] if len(saved) > 1 else 'raw') if saved[0] else None
        args = [a for a in self._args if not a.startswith('-')]
        if args:
            topic = args[0]
            parent, _, last = topic.rpartition('/')
            select = (parent, last) if last in ('compressed', 'compressedDepth') else (topic, 'raw')
        self.update_topic_list(select)

    def shutdown_plugin(self):
        if self._sub is not None:
            self._sub.unregister()
        if self._mouse_pub is not None:
            self._mouse_pub.unregister()

    @staticmethod
    def add_arguments(parser):
        group = parser.add_argument_group('Options for rqt_image_view plugin')
        group.add_argument('topic', nargs='?', help='The topic to subscribe to')
