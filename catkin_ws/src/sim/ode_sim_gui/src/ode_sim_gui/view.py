"""The 3D view: ode_sim.engine.render's offscreen OpenGL renderer (the one the simulated
cameras use) draws the scene into an image that this widget paints; the mouse moves an
OrbitCamera as in Gazebo (left drag orbit, middle or shift + left drag pan, wheel zoom towards
the cursor; a click selects the model under the cursor)."""
import math
import time

import numpy as np
from PyQt5 import QtCore, QtGui, QtWidgets

from ode_sim.engine import gl
from ode_sim.engine.raycast import RayCaster
from ode_sim.engine.render import Renderer
from ode_sim_gui.orbit import OrbitCamera

HFOV = math.radians(60.0)
CLICK_PIXELS = 4
FAST_FRAME = 0.040          # s: a full frame slower than this -> half resolution while moving
INTERACTIVE_SCALE = 0.5
STILL_MS = 250              # the full-resolution frame this long after the last change


class ViewRenderer(Renderer):
    """The window's renderer: the cameras' Renderer (same shaders, same materials and lights),
    with what only the window needs cheaper.

    * The image is read back as RGBX into one buffer kept for the renderer's life (a QImage is
      laid over it: no copies; GL reads RGBA without repacking).
    * Opaque shapes are drawn nearest first and ground planes last, so that llvmpipe's depth
      test rejects hidden pixels before shading them (a camera's draw order is kept as it is).
    * The still part of the scene is cached: a shape whose pose has changed since the scene was
      set is "moving"; while the camera stays where it is, the other shapes are drawn once into
      a second framebuffer (colour and depth), and each frame copies it and draws only the
      moving shapes (and the transparent ones) over it. A camera that moves, or a shape that
      starts moving, drops the cache (rebuilt on the next frame the camera is still).
    * Static shapes' (the grid's) model matrices are computed once per scene.
    """

    def __init__(self, width, height, hfov, near=0.05, far=500.0):
        self._cache_fbo = self._cache_rbs = None
        super().__init__(width, height, hfov, near=near, far=far, depth=False)
        self.rgbx = np.zeros((self.height, self.width, 4), dtype=np.uint8)
        self._static = {}
        self.cached = False             # the last frame was drawn over the cache

    def set_scene(self, shapes, lights=(), ambient=(0.4, 0.4, 0.4, 1),
                  background=(0.7, 0.7, 0.7, 1)):
        super().set_scene(shapes, lights=lights, ambient=ambient, background=background)
        self._static = {id(s): _model_bytes(s) for s, *_ in self._shapes if s.static}
        self._last = {}                 # id(shape) -> model matrix bytes of the last frame
        self._moving = set()            # id(shape) of shapes that moved since set_scene
        self._cache_view = None         # viewproj the cache was drawn with, or None
        self._prev_view = None

    def render_rgbx(self, camera_pose):
        """Draw a frame into `self.rgbx` ((height, width, 4) uint8, row 0 at the top, the 4th
        byte 255) and return it."""
        cam = camera_pose.matrix()
        eye = cam[:3, 3]
        viewproj = (self._proj @ np.linalg.inv(cam)).T.astype('f4').tobytes()
        still, moving, blended = [], [], []
        last, self._last = self._last, {}
        for s, vao, u, tex, textured in self._shapes:
            k = id(s)
            model = self._static.get(k)
            if model is None:
                pose = s.world_pose()
                model = _matrix_bytes(pose)
                self._last[k] = model
                if k not in self._moving and k in last and last[k] != model:
                    self._moving.add(k)
                    self._cache_view = None
                p = pose.p
            else:
                p = s.world_pose().p if u[-1] >= 1.0 else None
            item = (model, vao, u, tex, textured)
            if u[-1] < 1.0:
                blended.append(item)
                continue
            far = math.inf if s.geometry.kind == 'plane' else float(np.dot(p - eye, p - eye))
            (moving if k in self._moving else still).append((far, len(still) + len(moving), item))
        still.sort(key=lambda t: t[:2])
        moving.sort(key=lambda t: t[:2])
        still = [it for _, _, it in still]
        over = [it for _, _, it in moving] + blended
        if self._cache_view == viewproj:
            mode = 'cached'
        elif self._prev_view == viewproj:
            mode = 'build'              # the camera is still: cache the still shapes
        else:
            mode = 'full'
        self._prev_view = viewproj
        gl.run(self._gl_frame, viewproj, tuple(float(v) for v in eye), still, over, mode)
        if mode == 'build':
            self._cache_view = viewproj
        elif mode == 'full':
            self._cache_view = None
        self.cached = mode == 'cached'
        if blended:
            self.rgbx[:, :, 3] = 255        # blending lowered alpha; Qt's RGBX wants 255
        return self.rgbx

    def _gl_frame(self, viewproj, eye, still, over, mode):
        ctx = gl.context()
        if mode == 'full':
            self._gl_draw(viewproj, eye, still + over)
        else:
            if mode == 'build':
                if self._cache_fbo is None:
                    rbs = (ctx.renderbuffer((self.width, self.height), components=4),
                           ctx.depth_renderbuffer((self.width, self.height)))
                    self._cache_fbo = ctx.framebuffer(color_attachments=[rbs[0]],
                                                      depth_attachment=rbs[1])
                    self._cache_rbs = rbs
                main, self._fbo = self._fbo, self._cache_fbo
                try:
                    self._gl_draw(viewproj, eye, still)
                finally:
                    self._fbo = main
            ctx.copy_framebuffer(self._fbo, self._cache_fbo)
            self._gl_draw(viewproj, eye, over, clear=False)
        self._fbo.read_into(self.rgbx, components=4, alignment=1)

    def _gl_release(self):
        super()._gl_release()
        for obj in [self._cache_fbo] + list(self._cache_rbs or ()):
            if obj is not None:
                obj.release()
        self._cache_fbo = self._cache_rbs = None


def _matrix_bytes(pose):
    return pose.matrix().T.astype('f4').tobytes()


def _model_bytes(shape):
    return _matrix_bytes(shape.world_pose())


class View3D(QtWidgets.QWidget):
    selected = QtCore.pyqtSignal(object)          # model name or None
    ground_clicked = QtCore.pyqtSignal(float, float)   # x, y on the ground (placing mode)
    ground_dragged = QtCore.pyqtSignal(float, float, bool)   # x, y, finished (move tool)
    wall_drawn = QtCore.pyqtSignal(float, float, float, float, bool)   # x0 y0 x1 y1, finished

    def __init__(self, scene, parent=None):
        super().__init__(parent)
        self.scene = scene
        self.camera = OrbitCamera(640, 480, HFOV)
        self.setMinimumSize(160, 120)
        self.setMouseTracking(True)
        self.setFocusPolicy(QtCore.Qt.StrongFocus)
        self.setSizePolicy(QtWidgets.QSizePolicy.Expanding, QtWidgets.QSizePolicy.Expanding)
        self._renderers = {}           # scale -> Renderer
        self._dirty = set()
        self._image = None
        self._image_buffer = None
        self._want_full = False
        self._full_view = None          # camera of the last full-resolution frame
        self.full_frame_cost = 0.0
        self._full_timer = QtCore.QTimer(self)
        self._full_timer.setSingleShot(True)
        self._full_timer.setInterval(STILL_MS)
        self._full_timer.timeout.connect(self._full_frame)
        self._press = None
        self._last = None
        self.mode = 'select'           # 'select' | 'place' | 'translate' | 'rotate' | 'wall'
        self._wall_start = None
        self.frames = 0
        self.frame_times = []
        self._caster = None

    # ------------------------------------------------------------ drawing
    def scene_changed(self):
        """The set of shapes changed (models came or went, selection changed)."""
        self._dirty = set(self._renderers)
        self._caster = None

    def _renderer_for(self, scale):
        w = max(int(round(self.width() * scale)), 1)
        h = max(int(round(self.height() * scale)), 1)
        r = self._renderers.get(scale)
        if r is None or (r.width, r.height) != (w, h):
            if r is not None:
                r.release()
            r = self._renderers[scale] = ViewRenderer(w, h, HFOV, near=0.05, far=500.0)
            self._dirty.add(scale)
        if scale in self._dirty:
            r.set_scene(self.scene.shapes(), lights=self.scene.lights(),
                        ambient=self.scene.ambient(), background=self.scene.background())
            self._dirty.discard(scale)
        return r

    def render_now(self, scale=1.0):
        """Draw one frame into the image (does not paint); `scale` < 1 renders fewer pixels
        (the same camera, the image is stretched over the view when painted)."""
        t0 = time.perf_counter()
        self.camera.resize(max(self.width(), 1), max(self.height(), 1))
        rgbx = self._renderer_for(scale).render_rgbx(self.camera.pose())
        h, w, _ = rgbx.shape
        if self._image is None or self._image_buffer is not rgbx:
            # the QImage lies over the renderer's buffer: each frame is read back into it
            self._image = QtGui.QImage(rgbx.data, w, h, 4 * w, QtGui.QImage.Format_RGBX8888)
            self._image_buffer = rgbx
        self.frames += 1
        dt = time.perf_counter() - t0
        self.frame_times.append(dt)
        del self.frame_times[:-100]
        if scale == 1.0 and not self._renderers[scale].cached:
            self.full_frame_cost = dt       # what a frame costs when the cache cannot serve

    def paintEvent(self, event):
        # software GL: while the camera moves, a full frame that costs more than FAST_FRAME is
        # drawn at half resolution; the full one follows once it is still. With the camera
        # still, models that move are drawn over the cached still scene (ViewRenderer): full
        # resolution.
        view = self.camera.pose().matrix().tobytes()
        fast = not self._want_full and self.full_frame_cost > FAST_FRAME and \
            view != self._full_view
        self._want_full = False
        self.render_now(INTERACTIVE_SCALE if fast else 1.0)
        if fast:
            self._full_timer.start()
        else:
            self._full_view = view
        p = QtGui.QPainter(self)
        p.drawImage(self.rect(), self._image)
        p.end()

    def _full_frame(self):
        self._want_full = True
        self.update()

    def last_rgb(self):
        """The last frame drawn, (height, width, 3) uint8 (a view of the renderer's buffer)."""
        return self._image_buffer[:, :, :3] if self._image_buffer is not None else None

    # -------------------------------------------------------------- mouse
    def mousePressEvent(self, e):
        self._press = (e.pos(), e.button(), e.modifiers())
        self._last = e.pos()
        if self.mode == 'wall' and e.button() == QtCore.Qt.LeftButton \
                and not e.modifiers() & QtCore.Qt.ShiftModifier:
            self._wall_start = self.camera.ground_point(e.x(), e.y())
        if self.mode in ('translate', 'rotate') and e.button() == QtCore.Qt.LeftButton \
                and self.scene.selected and not e.modifiers() & QtCore.Qt.ShiftModifier:
            self._drag_start = self.camera.ground_point(e.x(), e.y())

    def mouseMoveEvent(self, e):
        if self._last is None or not e.buttons():
            return
        dx, dy = e.x() - self._last.x(), e.y() - self._last.y()
        self._last = e.pos()
        b = e.buttons()
        shift = e.modifiers() & QtCore.Qt.ShiftModifier
        if self._wall_start is not None and b & QtCore.Qt.LeftButton:
            g = self.camera.ground_point(e.x(), e.y())
            if g is not None:
                s = self._wall_start
                self.wall_drawn.emit(float(s[0]), float(s[1]), float(g[0]), float(g[1]), False)
            return
        if self.mode in ('translate', 'rotate') and b & QtCore.Qt.LeftButton and not shift \
                and self.scene.selected and getattr(self, '_drag_start', None) is not None:
            g = self.camera.ground_point(e.x(), e.y())
            if g is not None:
                self.ground_dragged.emit(float(g[0]), float(g[1]), False)
            return
        if b & QtCore.Qt.MiddleButton or (b & QtCore.Qt.LeftButton and shift):
            self.camera.pan(dx, dy)
        elif b & QtCore.Qt.LeftButton:
            self.camera.orbit(dx, dy)
        elif b & QtCore.Qt.RightButton:
            self.camera.zoom(-dy / 20.0)
        self.update()

    def mouseReleaseEvent(self, e):
        if self._press is None:
            return
        pos, button, _ = self._press
        self._press = None
        moved = (e.pos() - pos).manhattanLength()
        if self._wall_start is not None:
            s, self._wall_start = self._wall_start, None
            g = self.camera.ground_point(e.x(), e.y())
            if g is not None and moved > CLICK_PIXELS:
                self.wall_drawn.emit(float(s[0]), float(s[1]), float(g[0]), float(g[1]), True)
            return
        if getattr(self, '_drag_start', None) is not None:
            self._drag_start = None
            if moved > CLICK_PIXELS:
                g = self.camera.ground_point(e.x(), e.y())
                if g is not None:
                    self.ground_dragged.emit(float(g[0]), float(g[1]), True)
                return
        if button != QtCore.Qt.LeftButton or moved > CLICK_PIXELS:
            return
        if self.mode == 'place':
            g = self.camera.ground_point(e.x(), e.y())
            if g is not None:
                self.ground_clicked.emit(float(g[0]), float(g[1]))
            return
        self.selected.emit(self.pick(e.x(), e.y()))

    def wheelEvent(self, e):
        notches = e.angleDelta().y() / 120.0
        if notches:
            self.camera.zoom(notches, e.pos().x(), e.pos().y())
            self.update()

    def pick(self, x, y):
        """Name of the model whose collision is first under pixel (x, y), or None."""
        if self._caster is None:
            shapes = self.scene.collisions()
            self._caster = RayCaster(shapes, core='python') if shapes else False
        if not self._caster:
            return None
        o, d = self.camera.ray(x, y)
        t, who = self._caster.cast_hits(o[None, :], d[None, :], 1000.0)
        k = int(who[0])
        return self._caster.shapes[k].model if k >= 0 else None

    def reset_view(self):
        self.camera.reset()
        self.update()

    def release(self):
        self._full_timer.stop()
        for r in self._renderers.values():
            r.release()
        self._renderers = {}
