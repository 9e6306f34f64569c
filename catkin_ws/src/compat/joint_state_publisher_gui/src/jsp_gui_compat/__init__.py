"""Run Debian's joint_state_publisher_gui with Qt's integer setters made to accept floats.

Debian 12 ships joint_state_publisher_gui 1.15.1, written for Python 3 on PyQt5 versions that
converted floats silently: `slider.setValue(RANGE/2)` raises TypeError with Python 3.11's
PyQt5 5.15, so the node dies on start and no /joint_states are published. Rounding the value
is what the older PyQt did.
"""
import signal
import sys
import threading

_INT_SETTERS = ('setValue', 'setMinimum', 'setMaximum')


def _rounding(setter):
    def set_rounded(self, value):
        return setter(self, int(round(value)))
    set_rounded.__name__ = setter.__name__
    return set_rounded


def patch_qt():
    """Make QSlider/QSpinBox integer setters accept floats (idempotent)."""
    from python_qt_binding.QtWidgets import QSlider, QSpinBox
    for cls in (QSlider, QSpinBox):
        for name in _INT_SETTERS:
            setter = getattr(cls, name)
            if not getattr(setter, '_course_rounding', False):
                wrapped = _rounding(setter)
                wrapped._course_rounding = True
                setattr(cls, name, wrapped)
    # QSlider.setRange(min, max) too
    rng = QSlider.setRange
    if not getattr(rng, '_course_rounding', False):
        def set_range(self, lo, hi):
            return rng(self, int(round(lo)), int(round(hi)))
        set_range._course_rounding = True
        QSlider.setRange = set_range


def main():
    """The node as Debian's script runs it, after patch_qt()."""
    import rospy
    from python_qt_binding.QtWidgets import QApplication
    patch_qt()
    import joint_state_publisher
    import joint_state_publisher_gui   # Debian's module (/usr/lib/python3/dist-packages)

    rospy.init_node('joint_state_publisher_gui')
    app = QApplication(sys.argv)
    app.setApplicationDisplayName('Joint State Publisher')
    num_rows = joint_state_publisher.get_param('num_rows', 0)
    gui = joint_state_publisher_gui.JointStatePublisherGui(
        'Node: ' + rospy.get_name(), joint_state_publisher.JointStatePublisher(), num_rows)
    gui.show()
    gui.sliderUpdateTrigger.emit()
    threading.Thread(target=gui.jsp.loop, daemon=True).start()
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    return app.exec_()
