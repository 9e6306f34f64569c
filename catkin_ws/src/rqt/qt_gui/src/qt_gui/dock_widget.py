"""The dock a plugin widget lives in; tells its handler when the user closes it."""
from python_qt_binding.QtCore import Signal
from python_qt_binding.QtGui import QIcon
from python_qt_binding.QtWidgets import (QDockWidget, QHBoxLayout, QLabel, QStyle, QToolButton,
                                         QWidget)


class DockWidget(QDockWidget):
    closed = Signal(object)

    def __init__(self, title, configure=None, hide_title=False, closable=True):
        super(DockWidget, self).__init__(title)
        self._closing_by_framework = False
        self._configure = configure
        if hide_title or configure is not None:
            bar = QWidget(self)
            layout = QHBoxLayout(bar)
            layout.setContentsMargins(4, 1, 1, 1)
            self._title_label = QLabel(title)
            if hide_title:
                self._title_label.hide()
            layout.addWidget(self._title_label, 1)
            if configure is not None:
                gear = QToolButton(bar)
                gear.setObjectName('configuration_button')
                gear.setIcon(QIcon.fromTheme('emblem-system',
                                             self.style().standardIcon(QStyle.SP_FileDialogDetailedView)))
                gear.setToolTip('Configuration')
                gear.setAutoRaise(True)
                gear.clicked.connect(lambda: configure())
                layout.addWidget(gear)
            if closable:
                close = QToolButton(bar)
                close.setObjectName('close_button')
                close.setIcon(self.style().standardIcon(QStyle.SP_TitleBarCloseButton))
                close.setAutoRaise(True)
                close.clicked.connect(self.close)
                layout.addWidget(close)
            self.setTitleBarWidget(bar)
            self.windowTitleChanged.connect(self._title_label.setText)

    def close_by_framework(self):
        self._closing_by_framework = True
        self.close()

    def closeEvent(self, event):
        super(DockWidget, self).closeEvent(event)
        if not self._closing_by_framework:
            self.closed.emit(self)
