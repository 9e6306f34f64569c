"""The left panel's tabs: World (the world tree, a model's pose editable in place, its
properties from the simulator) and Insert (the model library with thumbnails)."""
import math
import threading

from PyQt5 import QtCore, QtGui, QtWidgets

from ode_sim.description.transforms import Pose, quat_from_rpy
from ode_sim_gui.client import SimError

MODEL_ROLE = QtCore.Qt.UserRole


class WorldPanel(QtWidgets.QWidget):
    def __init__(self, window):
        super().__init__(window)
        self.window = window
        lay = QtWidgets.QVBoxLayout(self)
        lay.setContentsMargins(2, 2, 2, 2)
        self.tree = QtWidgets.QTreeWidget(self)
        self.tree.setHeaderHidden(True)
        self.tree.itemSelectionChanged.connect(self._tree_selected)
        lay.addWidget(self.tree, 3)
        self.props = QtWidgets.QWidget(self)
        form = QtWidgets.QFormLayout(self.props)
        form.setContentsMargins(2, 2, 2, 2)
        self.lbl_name = QtWidgets.QLabel('-')
        form.addRow('name', self.lbl_name)
        self.pose_boxes = []
        for label in ('x', 'y', 'z', 'roll', 'pitch', 'yaw'):
            sb = QtWidgets.QDoubleSpinBox(self.props)
            sb.setDecimals(3)
            sb.setRange(-1e6, 1e6) if label in ('x', 'y', 'z') else sb.setRange(-math.pi * 2, math.pi * 2)
            sb.setSingleStep(0.1)
            sb.setKeyboardTracking(False)
            sb.editingFinished.connect(self.apply_pose)
            form.addRow(label, sb)
            self.pose_boxes.append(sb)
        self.lbl_static = QtWidgets.QLabel('-')
        self.lbl_self_collide = QtWidgets.QLabel('-')
        self.lbl_mass = QtWidgets.QLabel('-')
        form.addRow('static', self.lbl_static)
        form.addRow('self_collide', self.lbl_self_collide)
        form.addRow('mass (kg)', self.lbl_mass)
        lay.addWidget(self.props, 2)
        self.props.setEnabled(False)
        self._items = {}
        self._editing = False

    # ---------------------------------------------------------------- tree
    def world_changed(self):
        scene = self.window.scene
        w = scene.world
        self.tree.blockSignals(True)
        self.tree.clear()
        self._items = {}
        if w is None:
            self.tree.blockSignals(False)
            return
        QTI = QtWidgets.QTreeWidgetItem
        sc = QTI(self.tree, ['Scene'])
        QTI(sc, ['ambient %s' % ' '.join('%g' % v for v in w.scene.ambient)])
        QTI(sc, ['background %s' % ' '.join('%g' % v for v in w.scene.background)])
        QTI(sc, ['shadows %s' % str(w.scene.shadows).lower()])
        ph = QTI(self.tree, ['Physics'])
        QTI(ph, ['gravity %s' % ' '.join('%g' % v for v in w.gravity)])
        QTI(ph, ['max_step_size %g' % w.physics.max_step_size])
        QTI(ph, ['real_time_update_rate %g' % w.physics.real_time_update_rate])
        QTI(ph, ['real_time_factor %g' % w.physics.real_time_factor])
        models = QTI(self.tree, ['Models'])
        for m in w.models:
            it = QTI(models, [m.name])
            it.setData(0, MODEL_ROLE, m.name)
            self._items[m.name] = it
            for link in m.links:
                li = QTI(it, ['link: %s' % link.name])
                li.setData(0, MODEL_ROLE, m.name)
                for v in link.visuals:
                    QTI(li, ['visual: %s (%s)' % (v.name, v.geometry.kind)]).setData(0, MODEL_ROLE, m.name)
                for c in link.collisions:
                    QTI(li, ['collision: %s (%s)' % (c.name, c.geometry.kind)]).setData(0, MODEL_ROLE, m.name)
            for j in m.joints:
                QTI(it, ['joint: %s (%s)' % (j.name, j.type)]).setData(0, MODEL_ROLE, m.name)
        lights = QTI(self.tree, ['Lights'])
        for light in w.lights:
            it = QTI(lights, ['%s (%s)' % (light.name, light.type)])
            it.setData(0, MODEL_ROLE, light.name)
            self._items[light.name] = it
        models.setExpanded(True)
        lights.setExpanded(True)
        self.tree.blockSignals(False)
        self.select(scene.selected)

    def _tree_selected(self):
        items = self.tree.selectedItems()
        name = items[0].data(0, MODEL_ROLE) if items else None
        self.window.select(name)

    def select(self, name):
        it = self._items.get(name)
        self.tree.blockSignals(True)
        self.tree.clearSelection()
        if it is not None:
            it.setSelected(True)
            self.tree.scrollToItem(it)
        self.tree.blockSignals(False)
        self._show_properties(name)

    # ---------------------------------------------------------- properties
    def _show_properties(self, name):
        scene = self.window.scene
        is_model = name is not None and scene.model(name) is not None
        self.props.setEnabled(is_model)
        self.lbl_name.setText(name or '-')
        self.lbl_static.setText('-')
        self.lbl_self_collide.setText('-')
        self.lbl_mass.setText('-')
        if not is_model:
            for sb in self.pose_boxes:
                sb.blockSignals(True)
                sb.setValue(0.0)
                sb.blockSignals(False)
            return
        self.poses_changed(force=True)
        try:
            mp = self.window.client.model_properties(name)
            self.lbl_static.setText(str(bool(mp.is_static)).lower())
            collide, mass = [], 0.0
            for body in mp.body_names:
                lp = self.window.client.link_properties('%s::%s' % (name, body))
                mass += lp.mass
            for link in scene.model(name).links:
                collide.append(link.self_collide)
            self.lbl_self_collide.setText(str(any(collide)).lower())
            self.lbl_mass.setText('%g' % mass)
        except SimError as e:
            self.window.statusBar().showMessage(str(e), 10000)

    def poses_changed(self, force=False):
        name = self.window.scene.selected
        if not name or self.window.scene.model(name) is None:
            return
        if not force and any(sb.hasFocus() for sb in self.pose_boxes):
            return                      # the user is typing
        pose = self.window.scene.model_pose(name)
        vals = list(pose.p) + list(pose.rpy())
        for sb, v in zip(self.pose_boxes, vals):
            sb.blockSignals(True)
            sb.setValue(float(v))
            sb.blockSignals(False)

    def apply_pose(self):
        name = self.window.scene.selected
        if not name or self.window.scene.model(name) is None:
            return
        v = [sb.value() for sb in self.pose_boxes]
        cur = self.window.scene.model_pose(name)
        new = Pose(v[:3], quat_from_rpy(*v[3:]))
        if max(abs(a - b) for a, b in zip(list(cur.p) + list(cur.rpy()), v)) < 5e-4:
            return
        self.window.move_model(name, new)


class InsertPanel(QtWidgets.QWidget):
    """The model library (ode_sim.description.library: the project's models, GAZEBO_MODEL_PATH,
    ~/.gazebo/models) with thumbnails, and on request the online model database (as Gazebo's
    Insert tab lists it; its models are downloaded when inserted); click an entry, then click on
    the ground."""

    def __init__(self, window, library=None):
        super().__init__(window)
        self.window = window
        lay = QtWidgets.QVBoxLayout(self)
        lay.setContentsMargins(2, 2, 2, 2)
        self.list = QtWidgets.QListWidget(self)
        self.list.setIconSize(QtCore.QSize(64, 64))
        self.list.itemClicked.connect(self._clicked)
        lay.addWidget(self.list)
        self.btn_database = QtWidgets.QPushButton('Connect to the model database', self)
        self.btn_database.clicked.connect(self.load_database)
        lay.addWidget(self.btn_database)
        self.status = QtWidgets.QLabel('', self)
        self.status.setWordWrap(True)
        lay.addWidget(self.status)
        self.entries = []
        self.error = None
        self._library = library
        self._fetch = None              # (thread, result) while the database is fetched
        QtCore.QTimer.singleShot(0, self.load)

    def _lib(self):
        if self._library is None:
            from ode_sim.description import library
            self._library = library
        return self._library

    def load(self):
        try:
            lib = self._lib()
            entries = list(lib.list_models())
        except Exception as e:  # noqa: BLE001 - ImportError, ModelError, OSError: one line
            self.error = 'model library: %s' % e
            self.list.addItem(self.error)
            return
        self._show(lib, entries)

    def load_database(self):
        """Fetch the model database's list in a thread (the window stays live); then its
        models are listed under 'database', or one line says why it cannot be reached."""
        if self._fetch is not None:
            return
        lib = self._lib()
        result = {}

        def work():
            try:
                result['entries'] = list(lib.list_models(database=True))
            except Exception as e:  # noqa: BLE001 - unreachable, malformed: one line
                result['error'] = str(e)
        t = threading.Thread(target=work, name='model database', daemon=True)
        self._fetch = (t, result)
        self.btn_database.setEnabled(False)
        self.status.setText('connecting to the model database ...')
        t.start()
        QtCore.QTimer.singleShot(100, self._database_done)

    def _database_done(self):
        t, result = self._fetch
        if t.is_alive():
            QtCore.QTimer.singleShot(100, self._database_done)
            return
        self._fetch = None
        self.btn_database.setEnabled(True)
        if 'error' in result:
            self.status.setText('model database: %s' % result['error'])
            return
        n = sum(1 for e in result['entries'] if e.source == 'database')
        self.status.setText('model database: %d models not on this machine' % n)
        self._show(self._lib(), result['entries'])

    def _show(self, lib, entries):
        self.entries = entries
        self.list.clear()
        source = None
        for entry in self.entries:
            if entry.source != source:
                source = entry.source
                head = QtWidgets.QListWidgetItem(source)
                head.setFlags(QtCore.Qt.NoItemFlags)
                f = head.font()
                f.setBold(True)
                head.setFont(f)
                self.list.addItem(head)
            it = QtWidgets.QListWidgetItem(entry.title or entry.name)
            it.setData(MODEL_ROLE, entry)
            it.setToolTip(entry.uri)
            if entry.source == 'database':      # not downloaded yet: no thumbnail to draw
                it.setToolTip('%s (downloaded when inserted)' % entry.uri)
            else:
                try:
                    it.setIcon(QtGui.QIcon(lib.thumbnail(entry, size=64)))
                except Exception as e:  # noqa: BLE001 - a model that cannot be drawn: no icon
                    it.setToolTip('%s (no thumbnail: %s)' % (entry.uri, e))
            self.list.addItem(it)

    def entry(self, name):
        for e in self.entries:
            if e.name == name:
                return e
        return None

    def _clicked(self, item):
        entry = item.data(MODEL_ROLE)
        if entry is not None:
            self.window.begin_insert('include', entry)
