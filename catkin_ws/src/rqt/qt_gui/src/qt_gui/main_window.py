"""The main window: dock area, menus (File, Plugins, Running, Perspectives, Help), status line."""
import os

from python_qt_binding.QtCore import Signal
from python_qt_binding.QtGui import QIcon
from python_qt_binding.QtWidgets import (QAction, QFileDialog, QInputDialog, QMainWindow,
                                         QMessageBox)


def make_icon(icon):
    if not icon:
        return QIcon()
    if icon['type'] == 'theme':
        return QIcon.fromTheme(icon['value'])
    if icon['type'] == 'file' and os.path.isfile(icon['value']):
        return QIcon(icon['value'])
    return QIcon()


class MainWindow(QMainWindow):
    closing = Signal()

    def __init__(self, title='rqt'):
        super(MainWindow, self).__init__()
        self.setObjectName('MainWindow')
        self.setWindowTitle(title)
        self.setDockNestingEnabled(True)
        self.setDockOptions(QMainWindow.AnimatedDocks | QMainWindow.AllowNestedDocks |
                            QMainWindow.AllowTabbedDocks)
        self.main = None

    def closeEvent(self, event):
        self.closing.emit()
        super(MainWindow, self).closeEvent(event)

    # ---- menus --------------------------------------------------------------------------
    def build_menus(self, main):
        self.main = main
        bar = self.menuBar()
        file_menu = bar.addMenu('&File')
        quit_action = QAction('&Quit', self)
        quit_action.setShortcut('Ctrl+Q')
        quit_action.triggered.connect(self.close)
        file_menu.addAction(quit_action)
        self.plugins_menu = bar.addMenu('&Plugins')
        self.running_menu = bar.addMenu('&Running')
        self.perspectives_menu = bar.addMenu('P&erspectives')
        help_menu = bar.addMenu('&Help')
        about = QAction('&About', self)
        about.triggered.connect(lambda: QMessageBox.about(
            self, 'About rqt', 'rqt: a re-implementation of the ROS 1 rqt framework for the course '
            '(Python 3, PyQt5).'))
        help_menu.addAction(about)
        self.fill_plugins_menu()
        self.fill_running_menu()
        self.fill_perspectives_menu()
        main.plugin_manager.plugins_changed.connect(self.fill_running_menu)

    def fill_plugins_menu(self):
        menu = self.plugins_menu
        menu.clear()
        submenus = {}
        for d in sorted(self.main.plugin_manager.descriptors(), key=lambda d: d['label'].lower()):
            parent = menu
            path = ()
            for g in d['groups']:
                path += (g['label'],)
                if path not in submenus:
                    sub = parent.addMenu(make_icon(g['icon']), g['label'])
                    if g['statustip']:
                        sub.setStatusTip(g['statustip'])
                    submenus[path] = sub
                parent = submenus[path]
            action = QAction(make_icon(d['icon']), d['label'], self)
            action.setObjectName('plugin_action__' + d['plugin_id'])
            action.setData(d['plugin_id'])
            if d['statustip']:
                action.setStatusTip(d['statustip'])
            action.triggered.connect(lambda _c=False, pid=d['plugin_id']:
                                     self.main.plugin_manager.load_plugin(pid))
            parent.addAction(action)
        self._sort_menu(menu)

    def _sort_menu(self, menu):
        actions = menu.actions()
        if not actions:
            return
        for a in actions:
            menu.removeAction(a)
        subs = sorted([a for a in actions if a.menu()], key=lambda a: a.text().lower())
        leaves = sorted([a for a in actions if not a.menu()], key=lambda a: a.text().lower())
        for a in subs:
            menu.addAction(a)
            self._sort_menu(a.menu())
        for a in leaves:
            menu.addAction(a)

    def fill_running_menu(self):
        menu = self.running_menu
        menu.clear()
        for (pid, serial), handler in sorted(self.main.plugin_manager.running.items()):
            action = QAction('Close %s' % handler.label(), self)
            action.triggered.connect(lambda _c=False, h=handler:
                                     self.main.plugin_manager.unload_plugin(h))
            menu.addAction(action)

    def fill_perspectives_menu(self):
        menu = self.perspectives_menu
        menu.clear()
        for text, fn in (('&Create perspective...', self._create), ('&Remove perspective...', self._remove),
                         ('&Import...', self._import), ('&Export...', self._export)):
            a = QAction(text, self)
            a.triggered.connect(fn)
            menu.addAction(a)
        menu.addSeparator()
        for name in self.main.perspective_names():
            a = QAction(name, self)
            a.setCheckable(True)
            a.setChecked(name == self.main.perspective)
            a.triggered.connect(lambda _c=False, n=name: self.main.switch_perspective(n))
            menu.addAction(a)

    def _create(self):
        name, ok = QInputDialog.getText(self, 'Create perspective', 'Name:')
        if ok and name and not name.startswith('@'):
            self.main.switch_perspective(name, clone=True)

    def _remove(self):
        names = [n for n in self.main.perspective_names() if n != self.main.perspective]
        if not names:
            return
        name, ok = QInputDialog.getItem(self, 'Remove perspective', 'Name:', names, 0, False)
        if ok:
            self.main.remove_perspective(name)

    def _import(self):
        path, _ = QFileDialog.getOpenFileName(self, 'Import perspective', '', 'Perspectives (*.perspective)')
        if path:
            name = self.main.import_perspective(path)
            if name:
                self.main.switch_perspective(name)

    def _export(self):
        path, _ = QFileDialog.getSaveFileName(self, 'Export perspective', self.main.perspective + '.perspective',
                                              'Perspectives (*.perspective)')
        if path:
            if not path.endswith('.perspective'):
                path += '.perspective'
            self.main.export_perspective(path)
