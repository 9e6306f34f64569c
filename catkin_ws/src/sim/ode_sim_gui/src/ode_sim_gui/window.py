"""The simulator's window ("Gazebo"): menus, toolbar, the world tree and Insert tabs, the 3D
view and the bottom bar, on a SimClient (the /gazebo/* API; never the engine itself)."""
import math
import time

import numpy as np
from PyQt5 import QtCore, QtGui, QtWidgets

from ode_sim.description import walls
from ode_sim.description.transforms import Pose, quat_from_rpy
from ode_sim_gui import shapes as shape_sdf
from ode_sim_gui.client import SimError
from ode_sim_gui.scene import SceneModel
from ode_sim_gui.view import View3D

POLL_MS = 10                 # new poses looked for this often
FRAME_MS = 20                # poses -> view at most this often (50 frames/s)
STATS_MS = 200
ALIVE_MS = 1000


def format_time(seconds):
    """Gazebo's bottom-bar time: 'DD HH:MM:SS.mmm'."""
    ms = int(round(max(seconds, 0.0) * 1000))
    s, ms = divmod(ms, 1000)
    m, s = divmod(s, 60)
    h, m = divmod(m, 60)
    d, h = divmod(h, 24)
    return '%02d %02d:%02d:%02d.%03d' % (d, h, m, s, ms)


def pose_key(link_poses, model_poses):
    """All positions and quaternions as one array: redraw only when something moved."""
    vals = [np.concatenate((p.p, p.q)) for d in (link_poses, model_poses) for p in d.values()]
    return np.concatenate(vals) if vals else np.zeros(0)


def say(line):
    print(line, flush=True)


class MainWindow(QtWidgets.QMainWindow):
    def __init__(self, client, library=None):
        super().__init__()
        self.client = client
        self.scene = SceneModel()
        self.setWindowTitle('Gazebo')
        self.resize(1280, 860)
        self.view = View3D(self.scene, self)
        self.setCentralWidget(self.view)
        self._pending_insert = None        # (kind, what) while placing
        self._names_seen = None
        self._version = -1
        self._posed_at = 0.0
        self._pose_key = None
        self._connected = False
        self._closing_line = None
        self._library = library
        self._build_actions()
        self._build_menus()
        self._build_toolbar()
        self._build_bottom_bar()
        self._build_left_panel()
        self.view.selected.connect(self.select)
        self.view.ground_clicked.connect(self._place_at)
        self.view.ground_dragged.connect(self._drag_selected)
        self.view.wall_drawn.connect(self._wall_drawn)
        self.wall_segments = []
        self._timers = []
        for ms, fn in ((POLL_MS, self._poll), (STATS_MS, self._update_stats),
                       (ALIVE_MS, self._check_alive)):
            t = QtCore.QTimer(self)
            t.timeout.connect(fn)
            t.start(ms)
            self._timers.append(t)

    # =========================================================== building
    def _action(self, text, fn, shortcut=None, checkable=False, tip=None):
        a = QtWidgets.QAction(text, self)
        a.triggered.connect(fn)
        if shortcut:
            a.setShortcut(QtGui.QKeySequence(shortcut))
        a.setCheckable(checkable)
        if tip:
            a.setToolTip(tip)
        return a

    def _build_actions(self):
        self.act_save = self._action('Save World &As', self.save_world_dialog, 'Ctrl+Shift+S')
        self.act_quit = self._action('&Quit', self.close, 'Ctrl+Q')
        self.act_reset_poses = self._action('Reset Model Poses', self.reset_model_poses,
                                            'Ctrl+Shift+R')
        self.act_reset_world = self._action('Reset World', self.reset_world, 'Ctrl+R')
        self.act_delete = self._action('Delete', self.delete_selected, 'Delete')
        self.act_reset_view = self._action('Reset View', self.view.reset_view)
        self.act_follow = self._action('Follow', self._toggle_follow, checkable=True)
        self.mode_group = QtWidgets.QActionGroup(self)
        self.act_modes = {}
        for mode, text, key in (('select', 'Select', 'Esc'), ('translate', 'Translate', 'T'),
                                ('rotate', 'Rotate', 'R')):
            a = self._action(text, lambda _=False, m=mode: self.set_mode(m), key, checkable=True)
            self.mode_group.addAction(a)
            self.act_modes[mode] = a
        self.act_modes['select'].setChecked(True)
        self.act_wall = self._action('Wall', lambda _=False: self.set_mode('wall'), 'W',
                                     checkable=True,
                                     tip='Draw walls: drag on the ground; Enter makes them one '
                                         'static model, Esc drops them')
        self.mode_group.addAction(self.act_wall)
        self.act_modes['wall'] = self.act_wall
        self.act_finish_walls = self._action('Finish Walls', self.finish_walls,
                                             tip='Enter in the view does the same')
        self.act_shapes = {k: self._action(k.capitalize(),
                                           lambda _=False, k=k: self.begin_insert('shape', k),
                                           tip='Insert a %s: click on the ground' % k)
                           for k in shape_sdf.SHAPES}
        self.act_lights = {k: self._action('%s light' % k.capitalize(),
                                           lambda _=False, k=k: self.begin_insert('light', k),
                                           tip='Insert a %s light: click on the ground' % k)
                           for k in shape_sdf.LIGHTS}

    def _build_menus(self):
        mb = self.menuBar()
        m = mb.addMenu('&File')
        m.addAction(self.act_save)
        m.addSeparator()
        m.addAction(self.act_quit)
        m = mb.addMenu('&Edit')
        m.addAction(self.act_reset_poses)
        m.addAction(self.act_reset_world)
        m.addSeparator()
        m.addAction(self.act_delete)
        m = mb.addMenu('&Camera')
        m.addAction(self.act_reset_view)
        m.addAction(self.act_follow)

    def _build_toolbar(self):
        tb = self.addToolBar('Tools')
        tb.setObjectName('tools')
        for a in self.act_modes.values():
            tb.addAction(a)
        tb.addSeparator()
        for a in self.act_shapes.values():
            tb.addAction(a)
        tb.addSeparator()
        for a in self.act_lights.values():
            tb.addAction(a)
        tb.addSeparator()
        tb.addAction(self.act_delete)
        tb.addSeparator()
        tb.addAction(self.act_wall)
        self.spin_wall_height = QtWidgets.QDoubleSpinBox(tb)
        self.spin_wall_height.setRange(0.05, 20.0)
        self.spin_wall_height.setValue(walls.DEFAULT_HEIGHT)
        self.spin_wall_height.setPrefix('h ')
        self.spin_wall_height.setToolTip('wall height (m)')
        self.spin_wall_thickness = QtWidgets.QDoubleSpinBox(tb)
        self.spin_wall_thickness.setRange(0.01, 2.0)
        self.spin_wall_thickness.setValue(walls.DEFAULT_THICKNESS)
        self.spin_wall_thickness.setPrefix('t ')
        self.spin_wall_thickness.setToolTip('wall thickness (m)')
        tb.addWidget(self.spin_wall_height)
        tb.addWidget(self.spin_wall_thickness)
        tb.addAction(self.act_finish_walls)

    def _build_bottom_bar(self):
        bar = QtWidgets.QWidget(self)
        lay = QtWidgets.QHBoxLayout(bar)
        lay.setContentsMargins(4, 2, 4, 2)
        self.btn_play = QtWidgets.QToolButton(bar)
        self.btn_play.setText('Pause')
        self.btn_play.clicked.connect(self.toggle_pause)
        self.btn_step = QtWidgets.QToolButton(bar)
        self.btn_step.setText('Step')
        self.btn_step.clicked.connect(lambda: self.step(self.spin_steps.value()))
        self.spin_steps = QtWidgets.QSpinBox(bar)
        self.spin_steps.setRange(1, 1000000)
        self.spin_steps.setValue(1)
        self.spin_steps.setToolTip('steps per click of Step')
        self.lbl_rtf = QtWidgets.QLabel('Real Time Factor: -', bar)
        self.lbl_sim = QtWidgets.QLabel('Sim Time: -', bar)
        self.lbl_real = QtWidgets.QLabel('Real Time: -', bar)
        self.lbl_iter = QtWidgets.QLabel('Iterations: -', bar)
        self.lbl_fps = QtWidgets.QLabel('FPS: -', bar)
        for w in (self.btn_play, self.btn_step, self.spin_steps, self.lbl_rtf, self.lbl_sim,
                  self.lbl_real, self.lbl_iter, self.lbl_fps):
            lay.addWidget(w)
        lay.addStretch(1)
        self.statusBar().addPermanentWidget(bar, 1)
        self.statusBar().showMessage('waiting for the simulator (%s)' % self.client.ns)
        self._fps_mark = (time.monotonic(), 0)

    def _build_left_panel(self):
        from ode_sim_gui.panels import InsertPanel, WorldPanel
        dock = QtWidgets.QDockWidget('World', self)
        dock.setObjectName('left')
        dock.setFeatures(QtWidgets.QDockWidget.DockWidgetMovable)
        self.tabs = QtWidgets.QTabWidget(dock)
        self.world_panel = WorldPanel(self)
        self.insert_panel = InsertPanel(self, self._library)
        self.tabs.addTab(self.world_panel, 'World')
        self.tabs.addTab(self.insert_panel, 'Insert')
        dock.setWidget(self.tabs)
        self.addDockWidget(QtCore.Qt.LeftDockWidgetArea, dock)

    # ============================================================== polling
    def _poll(self):
        if not self._connected:
            return
        names = self.client.model_names()
        if names is not None and set(names) != self._names_seen:
            self.refresh_world()
        if self.client.version != self._version and \
                time.monotonic() - self._posed_at >= FRAME_MS / 1000.0:
            self._posed_at = time.monotonic()
            self._version = self.client.version
            lp, mp = self.client.poses()
            key = pose_key(lp, mp)
            if self._pose_key is None or key.shape != self._pose_key.shape or \
                    np.abs(key - self._pose_key).max() > 1e-5:
                self._pose_key = key
                self.scene.set_poses(lp, mp)
                self._follow()
                self.view.update()
                self.world_panel.poses_changed()

    def refresh_world(self):
        """Fetch the world SDF again (models or lights came or went) and rebuild the view."""
        try:
            sdf = self.client.world_sdf()
        except SimError as e:
            self.statusBar().showMessage(str(e))
            return
        try:
            self.scene.update_world(sdf)
        except Exception as e:  # noqa: BLE001 - ModelError and friends: one line
            self.statusBar().showMessage('cannot show the world: %s' % e)
            say('[WARN] gzclient: cannot show the world: %s' % e)
            return
        names = self.client.model_names()
        self._names_seen = set(names) if names is not None else set(self.scene.model_names())
        self.scene.set_poses(*self.client.poses())
        self.view.scene_changed()
        self.view.update()
        self.world_panel.world_changed()

    def _update_stats(self):
        s = self.client.stats
        now = time.monotonic()
        t0, f0 = self._fps_mark
        if now - t0 >= 1.0:
            self.lbl_fps.setText('FPS: %.1f' % ((self.view.frames - f0) / (now - t0)))
            self._fps_mark = (now, self.view.frames)
        if s is None:
            return
        self.lbl_rtf.setText('Real Time Factor: %.2f' % s.real_time_factor)
        self.lbl_sim.setText('Sim Time: %s' % format_time(s.sim_time.to_sec()))
        self.lbl_real.setText('Real Time: %s' % format_time(s.real_time.to_sec()))
        self.lbl_iter.setText('Iterations: %d' % s.iterations)
        self.btn_play.setText('Play' if s.paused else 'Pause')

    def _check_alive(self):
        up = self.client.available()
        if up and not self._connected:
            self._connected = True
            self.statusBar().showMessage('connected to the simulator (%s)' % self.client.ns, 3000)
            self.refresh_world()
        elif not up and self._connected:
            self._closing_line = ('gzclient: the simulator (%s) has exited; closing the window'
                                  % self.client.ns)
            say('[INFO] ' + self._closing_line)
            self.close()

    # ============================================================ actions
    def _run(self, what, fn, *args):
        try:
            return fn(*args)
        except SimError as e:
            self.statusBar().showMessage('%s: %s' % (what, e), 10000)
            say('[WARN] gzclient: %s: %s' % (what, e))
            return None

    def toggle_pause(self):
        s = self.client.stats
        if s is not None and s.paused:
            self._run('play', self.client.unpause)
        else:
            self._run('pause', self.client.pause)

    def step(self, steps):
        s = self.client.stats
        if s is not None and not s.paused:
            self._run('pause', self.client.pause)
        return self._run('step', self.client.step, steps)

    def reset_model_poses(self):
        self._run('Reset Model Poses', self.client.reset_world)

    def reset_world(self):
        self._run('Reset World', self.client.reset_simulation)

    def select(self, name):
        if name == self.scene.selected:
            return
        self.scene.selected = name
        self.view.scene_changed()
        self.view.update()
        self.world_panel.select(name)

    def delete_selected(self):
        name = self.scene.selected
        if not name:
            return
        if any(l.name == name for l in self.scene.lights()):
            ok = self._run('delete', self.client.delete_light, name)
        else:
            ok = self._run('delete', self.client.delete_model, name)
        self.select(None)
        self.refresh_world()
        return ok

    def set_mode(self, mode):
        if self.view.mode == 'wall' and mode != 'wall':
            self._set_wall_preview([])
            self.wall_segments = []
        self.view.mode = mode
        if mode in self.act_modes:
            self.act_modes[mode].setChecked(True)
        if mode != 'place':
            self._pending_insert = None
        if mode == 'wall':
            self.statusBar().showMessage('drag on the ground to draw walls; Enter: done, '
                                         'Esc: drop them', 10000)

    # ----------------------------------------------------------- wall tool
    def _set_wall_preview(self, segments):
        from ode_sim.description.model import Geometry, Material
        from ode_sim.engine.scene import ShapeInstance
        mat = Material(name='wall_preview', diffuse=(0.9, 0.9, 0.6, 1.0))
        prev = []
        for i, (size, c, yaw) in enumerate(shape_sdf.wall_boxes(
                segments, self.spin_wall_height.value(), self.spin_wall_thickness.value())):
            prev.append(ShapeInstance(key='wall_preview::%d' % i, model='', link='preview',
                                      geometry=Geometry(kind='box', size=size),
                                      static_pose=Pose(c, quat_from_rpy(0.0, 0.0, yaw)),
                                      color=mat.diffuse, material=mat))
        self.scene.extra = prev
        self.view.scene_changed()
        self.view.update()

    def _wall_drawn(self, x0, y0, x1, y1, finished):
        seg = (x0, y0, x1, y1)
        if finished:
            self.wall_segments.append(seg)
            self._set_wall_preview(self.wall_segments)
        else:
            self._set_wall_preview(self.wall_segments + [seg])

    def finish_walls(self):
        """The drawn walls become one static model (ode_sim.description.walls), spawned."""
        segs, self.wall_segments = self.wall_segments, []
        self._set_wall_preview([])
        if not segs:
            return None
        taken = set(self.scene.model_names())
        name = shape_sdf.unique_name('walls', taken)
        try:
            xml = walls.walls_model(name, segs, self.spin_wall_height.value(),
                                    self.spin_wall_thickness.value())
        except Exception as e:  # noqa: BLE001 - ModelError: one line
            self.statusBar().showMessage(str(e), 10000)
            return None
        self._run('insert %s' % name, self.client.spawn_sdf, name, xml, Pose())
        self.refresh_world()
        self.set_mode('select')
        return name

    def begin_insert(self, kind, what):
        """Insert: the next click on the ground places it (Esc cancels)."""
        self._pending_insert = (kind, what)
        self.view.mode = 'place'
        self.statusBar().showMessage('click on the ground to place %s' % (
            what if kind != 'include' else what.name), 10000)

    def _place_at(self, x, y):
        pending, self._pending_insert = self._pending_insert, None
        self.set_mode('select')
        if pending:
            self.insert(pending[0], pending[1], x, y)

    def insert(self, kind, what, x, y):
        """Spawn a shape ('shape', 'box'), a light ('light', 'point') or a library model
        ('include', entry with .name and .uri) at (x, y) on the ground; returns its name."""
        taken = set(self.scene.model_names()) | {l.name for l in self.scene.lights()}
        if kind == 'shape':
            name = shape_sdf.unique_name('unit_' + what, taken)
            xml, z = shape_sdf.shape_sdf(what, name), 0.5
        elif kind == 'light':
            name = shape_sdf.unique_name('user_%s_light' % what, taken)
            xml, z = shape_sdf.light_sdf(what, name), 1.0
        else:
            name = shape_sdf.unique_name(what.name, taken)
            xml, z = shape_sdf.include_sdf(what.uri), 0.0
        if self._run('insert %s' % name, self.client.spawn_sdf, name, xml,
                     Pose((x, y, z))) is None and kind != 'light':
            pass
        self.refresh_world()
        return name

    def move_model(self, name, pose):
        self._run('move %s' % name, self.client.set_model_pose, name, pose)

    def _drag_selected(self, x, y, finished):
        name = self.scene.selected
        if not name:
            return
        cur = self.scene.model_pose(name)
        if self.view.mode == 'translate':
            pose = Pose((x, y, cur.p[2]), cur.q)
        else:
            yaw = math.atan2(y - cur.p[1], x - cur.p[0])
            r, p, _ = cur.rpy()
            pose = Pose(cur.p, quat_from_rpy(r, p, yaw))
        self.move_model(name, pose)

    def _toggle_follow(self, on):
        self._follow_name = self.scene.selected if on else None

    def _follow(self):
        name = getattr(self, '_follow_name', None)
        if name:
            self.view.camera.focus = self.scene.model_pose(name).p.copy()

    def save_world(self, path):
        """File -> Save World As: the simulator's current world SDF into `path`."""
        sdf = self._run('Save World As', self.client.world_sdf)
        if sdf is None:
            return False
        try:
            with open(path, 'w') as f:
                f.write(sdf)
        except OSError as e:
            self.statusBar().showMessage('Save World As: %s: %s' % (path, e.strerror or e), 10000)
            say('[WARN] gzclient: Save World As: %s: %s' % (path, e.strerror or e))
            return False
        self.statusBar().showMessage('saved %s' % path, 5000)
        return True

    def save_world_dialog(self):
        path, _ = QtWidgets.QFileDialog.getSaveFileName(self, 'Save World As', 'my.world',
                                                        'World files (*.world *.sdf)')
        if path:
            self.save_world(path)

    def keyPressEvent(self, e):
        if e.key() == QtCore.Qt.Key_Escape:
            self.set_mode('select')
        elif e.key() == QtCore.Qt.Key_Delete:      # a key event the shortcut map did not take
            self.delete_selected()
        elif e.key() in (QtCore.Qt.Key_Return, QtCore.Qt.Key_Enter) and self.view.mode == 'wall':
            self.finish_walls()
        super().keyPressEvent(e)

    def closeEvent(self, e):
        for t in self._timers:
            t.stop()
        self.view.release()
        super().closeEvent(e)
