"""rqt_robot_steering plugin `RobotSteering`: sliders -> geometry_msgs/Twist on a chosen topic."""
from python_qt_binding.QtCore import Qt, QTimer
from python_qt_binding.QtGui import QKeySequence
from python_qt_binding.QtWidgets import (QDoubleSpinBox, QGridLayout, QHBoxLayout, QLabel,
                                         QLineEdit, QPushButton, QShortcut, QSlider, QVBoxLayout,
                                         QWidget)
from rqt_gui_py.plugin import Plugin

from rqt_robot_steering.steering import Steering, label, slider_limit


def _spin(value, lo, hi):
    s = QDoubleSpinBox()
    s.setRange(lo, hi)
    s.setSingleStep(0.1)
    s.setDecimals(2)
    s.setValue(value)
    return s


class RobotSteeringWidget(QWidget):

    def __init__(self, parent=None):
        super(RobotSteeringWidget, self).__init__(parent)
        self.setObjectName('RobotSteeringUi')
        self.setWindowTitle('Robot Steering')
        self.topic_line_edit = QLineEdit('/cmd_vel')
        self.topic_line_edit.setObjectName('topic_line_edit')
        self.linear_slider = QSlider(Qt.Vertical)
        self.linear_slider.setObjectName('x_linear_slider')
        self.angular_slider = QSlider(Qt.Horizontal)
        self.angular_slider.setObjectName('z_angular_slider')
        for s, lim in ((self.linear_slider, 1000), (self.angular_slider, 3000)):
            s.setRange(-lim, lim)
            s.setSingleStep(10)
            s.setPageStep(100)
            s.setValue(0)
        self.linear_label = QLabel('0.00 m/s')
        self.angular_label = QLabel('0.00 rad/s')
        self.max_x_linear_double_spin_box = _spin(1.0, 0.0, 10.0)
        self.min_x_linear_double_spin_box = _spin(-1.0, -10.0, 0.0)
        self.max_z_angular_double_spin_box = _spin(3.0, 0.0, 10.0)
        self.min_z_angular_double_spin_box = _spin(-3.0, -10.0, 0.0)
        self.stop_push_button = QPushButton('stop')
        self.increase_x_linear_push_button = QPushButton('+')
        self.reset_x_linear_push_button = QPushButton('0')
        self.decrease_x_linear_push_button = QPushButton('-')
        self.increase_z_angular_push_button = QPushButton('<')
        self.reset_z_angular_push_button = QPushButton('0')
        self.decrease_z_angular_push_button = QPushButton('>')

        top = QHBoxLayout()
        top.addWidget(QLabel('Topic'))
        top.addWidget(self.topic_line_edit, 1)
        top.addWidget(self.stop_push_button)
        grid = QGridLayout()
        lin = QVBoxLayout()
        lin.addWidget(self.max_x_linear_double_spin_box)
        lin.addWidget(self.increase_x_linear_push_button)
        lin.addWidget(self.linear_slider, 1, Qt.AlignHCenter)
        lin.addWidget(self.reset_x_linear_push_button)
        lin.addWidget(self.decrease_x_linear_push_button)
        lin.addWidget(self.min_x_linear_double_spin_box)
        lin.addWidget(self.linear_label)
        grid.addLayout(lin, 0, 0)
        ang = QHBoxLayout()
        ang.addWidget(self.min_z_angular_double_spin_box)
        ang.addWidget(self.increase_z_angular_push_button)
        ang.addWidget(self.angular_slider, 1)
        ang.addWidget(self.reset_z_angular_push_button)
        ang.addWidget(self.decrease_z_angular_push_button)
        ang.addWidget(self.max_z_angular_double_spin_box)
        angv = QVBoxLayout()
        angv.addStretch(1)
        angv.addLayout(ang)
        angv.addWidget(self.angular_label, 0, Qt.AlignHCenter)
        grid.addLayout(angv, 0, 1)
        layout = QVBoxLayout(self)
        layout.addLayout(top)
        layout.addLayout(grid, 1)


class RobotSteering(Plugin):

    def __init__(self, context):
        super(RobotSteering, self).__init__(context)
        self.setObjectName('RobotSteering')
        self._widget = w = RobotSteeringWidget()
        if context.serial_number() > 1:
            w.setWindowTitle(w.windowTitle() + (' (%d)' % context.serial_number()))
        self._steering = Steering()
        self._publisher = None
        w.topic_line_edit.textChanged.connect(self._on_topic_changed)
        w.stop_push_button.pressed.connect(self._stop)
        w.linear_slider.valueChanged.connect(self._on_linear)
        w.angular_slider.valueChanged.connect(self._on_angular)
        w.increase_x_linear_push_button.pressed.connect(lambda: self._step(w.linear_slider, w.linear_slider.pageStep()))
        w.reset_x_linear_push_button.pressed.connect(lambda: w.linear_slider.setValue(0))
        w.decrease_x_linear_push_button.pressed.connect(
            lambda: self._step(w.linear_slider, -w.linear_slider.pageStep()))
        w.increase_z_angular_push_button.pressed.connect(
            lambda: self._step(w.angular_slider, w.angular_slider.pageStep()))
        w.reset_z_angular_push_button.pressed.connect(lambda: w.angular_slider.setValue(0))
        w.decrease_z_angular_push_button.pressed.connect(
            lambda: self._step(w.angular_slider, -w.angular_slider.pageStep()))
        w.max_x_linear_double_spin_box.valueChanged.connect(lambda v: w.linear_slider.setMaximum(slider_limit(v)))
        w.min_x_linear_double_spin_box.valueChanged.connect(lambda v: w.linear_slider.setMinimum(slider_limit(v)))
        w.max_z_angular_double_spin_box.valueChanged.connect(lambda v: w.angular_slider.setMaximum(slider_limit(v)))
        w.min_z_angular_double_spin_box.valueChanged.connect(lambda v: w.angular_slider.setMinimum(slider_limit(v)))
        keys = [('w', w.linear_slider, 1, False), ('s', w.linear_slider, -1, False),
                ('a', w.angular_slider, 1, False), ('d', w.angular_slider, -1, False),
                ('Shift+w', w.linear_slider, 1, True), ('Shift+s', w.linear_slider, -1, True),
                ('Shift+a', w.angular_slider, 1, True), ('Shift+d', w.angular_slider, -1, True)]
        self._shortcuts = []
        for key, slider, sign, page in keys:
            sc = QShortcut(QKeySequence(key), w)
            sc.setContext(Qt.ApplicationShortcut)
            sc.activated.connect(lambda s=slider, g=sign, p=page:
                                 self._step(s, g * (s.pageStep() if p else s.singleStep())))
            self._shortcuts.append(sc)
        for key, fn in (('x', lambda: w.linear_slider.setValue(0)), ('z', lambda: w.angular_slider.setValue(0)),
                        ('space', self._stop), ('Shift+space', self._stop)):
            sc = QShortcut(QKeySequence(key), w)
            sc.setContext(Qt.ApplicationShortcut)
            sc.activated.connect(fn)
            self._shortcuts.append(sc)
        context.add_widget(w)
        self._on_topic_changed(w.topic_line_edit.text())
        self._timer = QTimer(self)
        self._timer.timeout.connect(self._send)
        self._timer.start(100)

    def _step(self, slider, delta):
        slider.setValue(slider.value() + delta)

    def _on_linear(self, value):
        self._steering.linear = value
        self._widget.linear_label.setText(label(value / 1000.0, 'm/s'))

    def _on_angular(self, value):
        self._steering.angular = value
        self._widget.angular_label.setText(label(value / 1000.0, 'rad/s'))

    def _stop(self):
        self._steering.stop()
        self._widget.linear_slider.setValue(0)
        self._widget.angular_slider.setValue(0)

    def _on_topic_changed(self, topic):
        import rospy
        from geometry_msgs.msg import Twist
        topic = str(topic).strip()
        if self._publisher is not None:
            self._publisher.unregister()
            self._publisher = None
        if topic == '':
            return
        try:
            self._publisher = rospy.Publisher(topic, Twist, queue_size=10)
        except Exception as e:
            import sys
            print('rqt_robot_steering: invalid topic "%s": %s' % (topic, e), file=sys.stderr)
            self._publisher = None
        self._steering._zero_sent = False

    def _send(self):
        if self._publisher is None:
            return
        cmd = self._steering.next_to_send()
        if cmd is None:
            return
        from geometry_msgs.msg import Twist
        twist = Twist()
        twist.linear.x, twist.angular.z = cmd
        try:
            self._publisher.publish(twist)
        except Exception:
            pass

    def save_settings(self, plugin_settings, instance_settings):
        w = self._widget
        instance_settings.set_value('topic', w.topic_line_edit.text())
        instance_settings.set_value('vx_max', w.max_x_linear_double_spin_box.value())
        instance_settings.set_value('vx_min', w.min_x_linear_double_spin_box.value())
        instance_settings.set_value('vw_max', w.max_z_angular_double_spin_box.value())
        instance_settings.set_value('vw_min', w.min_z_angular_double_spin_box.value())

    def restore_settings(self, plugin_settings, instance_settings):
        import rospy
        w = self._widget
        for key, box in (('vx_max', w.max_x_linear_double_spin_box), ('vx_min', w.min_x_linear_double_spin_box),
                         ('vw_max', w.max_z_angular_double_spin_box), ('vw_min', w.min_z_angular_double_spin_box)):
            value = rospy.get_param('~default_' + key, instance_settings.value(key, box.value()))
            try:
                box.setValue(float(value))
            except (TypeError, ValueError):
                pass
        topic = rospy.get_param('~default_topic', instance_settings.value('topic', w.topic_line_edit.text()))
        w.topic_line_edit.setText(str(topic))

    def shutdown_plugin(self):
        self._timer.stop()
        if self._publisher is not None:
            self._publisher.unregister()
            self._publisher = None
