"""Camera images by real OpenGL, offscreen: moderngl on Mesa's EGL (llvmpipe works, no display).

One EGL context per process, created on first use and shared by every Renderer (each has its
own framebuffer of its own size). All GL calls go through a module lock, so renderers may be
used from several threads, one at a time.

Camera convention (Gazebo's): the camera frame looks along +X, +Z is up, +Y is left. The image
is a pinhole projection with square pixels: focal length f = width / (2 tan(hfov / 2)) pixels,
principal point exactly at the image centre (pixel-centre coordinates (width-1)/2,
(height-1)/2 when pixel 0 is centred on 0), as Gazebo renders it. `camera_info_matrix` gives
the K and P matrices that gazebo_ros_camera_utils publishes by default; note that those put
cx, cy at (width+1)/2, (height+1)/2, one pixel right/down of the true centre — Gazebo's
long-standing default, kept for compatibility.

Depth: distance along the optical axis (the camera's X) in metres, float32; +inf where nothing
is hit or the surface is beyond `far` (also below `near`, things are clipped away). Gazebo's
depth camera plugin (gazebo_ros_openni_kinect) publishes such pixels as NaN in its 32FC1
depth image (everything outside (pointCloudCutoff, pointCloudCutoffMax)); the ROS-publishing
layer maps inf to NaN, this module keeps inf so that comparisons stay meaningful.

Lighting: scene ambient x colour, plus per light a Lambert term (light diffuse x colour) and a
little Blinn-Phong specular; both sides of a triangle are lit (normals face the viewer), no
culling, no shadows, colours are opaque (alpha ignored).
"""
import math
import threading

import numpy as np

from .model import ModelError
from .tessellate import tessellate

MAX_LIGHTS = 8
SPECULAR = 0.2          # material specular factor
SHININESS = 32.0

_VERTEX_SHADER = """
#version 330
uniform mat4 u_viewproj;
uniform mat4 u_model;
in vec3 in_pos;
in vec3 in_normal;
out vec3 v_world;
out vec3 v_normal;
void main() {
    vec4 w = u_model * vec4(in_pos, 1.0);
    v_world = w.xyz;
    v_normal = mat3(u_model) * in_normal;
    gl_Position = u_viewproj * w;
}
"""

_FRAGMENT_SHADER = """
#version 330
uniform vec4 u_color;
uniform vec3 u_ambient;
uniform vec3 u_eye;
uniform int u_nlights;
uniform vec4 u_light_vec[%(n)d];       // xyz: direction (w = 0) or position (w = 1), world
uniform vec3 u_light_diffuse[%(n)d];
uniform vec3 u_light_specular[%(n)d];
in vec3 v_world;
in vec3 v_normal;
out vec4 f_color;
void main() {
    vec3 n = normalize(v_normal);
    vec3 view = normalize(u_eye - v_world);
    if (dot(n, view) < 0.0) n = -n;
    vec3 c = u_ambient * u_color.rgb;
    for (int i = 0; i < u_nlights; ++i) {
        vec3 l = u_light_vec[i].w == 0.0 ? -u_light_vec[i].xyz
                                         : normalize(u_light_vec[i].xyz - v_world);
        float d = dot(n, l);
        if (d > 0.0) {
            c += d * u_light_diffuse[i] * u_color.rgb;
            float s = max(dot(n, normalize(l + view)), 0.0);
            c += %(spec)f * pow(s, %(shin)f) * u_light_specular[i];
        }
    }
    f_color = vec4(min(c, vec3(1.0)), 1.0);
}
""" % {'n': MAX_LIGHTS, 'spec': SPECULAR, 'shin': SHININESS}

_lock = threading.RLock()
_ctx = None
_prog = None


def _context():
    """The process's EGL context and shader program, created on first call."""
    global _ctx, _prog
    if _ctx is None:
        try:
            import moderngl
        except ImportError as e:
            raise ModelError('ode_sim.render: cannot import moderngl (%s): install the Debian '
                             'package python3-moderngl' % e) from None
        try:
            ctx = moderngl.create_standalone_context(backend='egl', require=330)
        except Exception as e:  # noqa: BLE001 - moderngl raises plain Exception
            raise ModelError('ode_sim.render: cannot create an offscreen OpenGL 3.3 context '
                             'through EGL (%s): install libegl1, libegl-mesa0 and '
                             'libgl1-mesa-dri' % str(e).strip().splitlines()[0]) from None
        try:
            prog = ctx.program(vertex_shader=_VERTEX_SHADER, fragment_shader=_FRAGMENT_SHADER)
        except Exception as e:  # noqa: BLE001
            ctx.release()
            raise ModelError('ode_sim.render: shader compilation failed on %s: %s'
                             % (ctx.info.get('GL_RENDERER', '?'), e)) from None
        _ctx, _prog = ctx, prog
    return _ctx, _prog


def focal_length(width, hfov):
    """Focal length in pixels for `width` pixels over the horizontal field of view `hfov`."""
    return width / (2.0 * math.tan(hfov / 2.0))


def camera_info_matrix(width, height, hfov, cx=None, cy=None, focal=None, hack_baseline=0.0):
    """(K 3x3, P 3x4) as gazebo_ros_camera_utils publishes them in sensor_msgs/CameraInfo.

    Defaults as the plugin's: focal (`focalLength` 0) = width / (2 tan(hfov/2)) for both axes,
    cx (`Cx`) = (width + 1) / 2, cy (`Cy`) = (height + 1) / 2, P[0,3] = -focal * hackBaseline.
    """
    f = focal_length(width, hfov) if not focal else float(focal)
    cx = (width + 1) / 2.0 if cx is None else float(cx)
    cy = (height + 1) / 2.0 if cy is None else float(cy)
    K = np.array([[f, 0.0, cx], [0.0, f, cy], [0.0, 0.0, 1.0]])
    P = np.array([[f, 0.0, cx, -f * hack_baseline], [0.0, f, cy, 0.0], [0.0, 0.0, 1.0, 0.0]])
    return K, P


# camera frame (X forward, Y left, Z up) -> OpenGL eye frame (x right, y up, looking along -z)
_CAM_TO_GL = np.array([[0.0, -1.0, 0.0, 0.0],
                       [0.0, 0.0, 1.0, 0.0],
                       [-1.0, 0.0, 0.0, 0.0],
                       [0.0, 0.0, 0.0, 1.0]])


def _check_color(name, value):
    try:
        v = [float(x) for x in value]
    except (TypeError, ValueError):
        v = []
    if len(v) not in (3, 4) or not all(math.isfinite(x) for x in v):
        raise ModelError('ode_sim.render: %s must be 3 or 4 finite numbers (RGB[A]), got %r'
                         % (name, value))
    return v[:3]


class Renderer:
    def __init__(self, width, height, hfov, near=0.1, far=100.0, depth=False):
        try:
            width, height = int(width), int(height)
            hfov, near, far = float(hfov), float(near), float(far)
        except (TypeError, ValueError):
            raise ModelError('ode_sim.render: camera needs numeric width, height, hfov, near, '
                             'far; got %r' % ((width, height, hfov, near, far),)) from None
        if width <= 0 or height <= 0:
            raise ModelError('ode_sim.render: camera image size must be positive, got %dx%d'
                             % (width, height))
        if not 0 < hfov < math.pi:
            raise ModelError('ode_sim.render: camera horizontal_fov must be in (0, pi) for a '
                             'pinhole camera, got %g rad' % hfov)
        if not 0 < near < far or not math.isfinite(far):
            raise ModelError('ode_sim.render: camera clip needs 0 < near < far, got near %g far %g'
                             % (near, far))
        self.width, self.height, self.hfov = width, height, hfov
        self.near, self.far, self.depth = near, far, bool(depth)
        self.focal = focal_length(width, hfov)
        # projection with square pixels; the Y row is negated so that GL's row 0 (read back
        # first) is the top of the image: readback needs no flip
        t = math.tan(hfov / 2.0)
        proj = np.zeros((4, 4))
        proj[0, 0] = 1.0 / t
        proj[1, 1] = -(width / height) / t
        proj[2, 2] = -(far + near) / (far - near)
        proj[2, 3] = -2.0 * far * near / (far - near)
        proj[3, 2] = -1.0
        self._proj = proj @ _CAM_TO_GL
        self._shapes = []
        self._meshes = {}                  # id(geometry) -> (geometry, vbo, ibo, vao)
        self._background = (0.7, 0.7, 0.7, 1.0)
        self._released = False
        with _lock:
            ctx, _ = _context()
            try:
                self._color_rb = ctx.renderbuffer((width, height), components=4)
                self._depth_rb = ctx.depth_renderbuffer((width, height))
                self._fbo = ctx.framebuffer(color_attachments=[self._color_rb],
                                            depth_attachment=self._depth_rb)
            except Exception as e:  # noqa: BLE001
                raise ModelError('ode_sim.render: cannot create a %dx%d framebuffer: %s'
                                 % (width, height, e)) from None
        self.set_scene([])

    # ---------------------------------------------------------------- scene
    def set_scene(self, shapes, lights=(), ambient=(0.4, 0.4, 0.4, 1), background=(0.7, 0.7, 0.7, 1)):
        """Shapes (ShapeInstance visuals) and lights (model.Light) to draw from now on.

        GPU meshes are cached per geometry object (by identity): calling again after models
        were added or removed uploads only the new geometries and frees the unused ones.
        """
        self._ambient = _check_color('scene ambient', ambient)
        bg = _check_color('scene background', background)
        self._background = tuple(bg) + (1.0,)
        if len(lights) > MAX_LIGHTS:
            lights = list(lights)[:MAX_LIGHTS]
        vec, dif, spe = [], [], []
        for light in lights:
            if light.type == 'directional':
                d = np.asarray(light.direction, dtype=float)
                n = np.linalg.norm(d)
                if not np.isfinite(n) or n == 0:
                    raise ModelError('ode_sim.render: light %r: direction %s is not a direction'
                                     % (light.name, list(light.direction)))
                vec += list(d / n) + [0.0]
            else:                       # point, spot: from the light's position, no falloff
                vec += list(light.pose.p) + [1.0]
            dif += _check_color('light %r diffuse' % light.name, light.diffuse)
            spe += _check_color('light %r specular' % light.name, light.specular)
        pad = MAX_LIGHTS - len(lights)
        self._lights = (len(lights),
                        np.array(vec + [0.0] * 4 * pad, dtype='f4').tobytes(),
                        np.array(dif + [0.0] * 3 * pad, dtype='f4').tobytes(),
                        np.array(spe + [0.0] * 3 * pad, dtype='f4').tobytes())
        with _lock:
            ctx, prog = _context()
            keep = {}
            draw = []
            for s in shapes:
                key = id(s.geometry)
                entry = keep.get(key) or self._meshes.get(key)
                if entry is None or entry[0] is not s.geometry:
                    pos, nrm, idx = tessellate(s.geometry, s.key)
                    if len(idx) == 0:
                        continue
                    data = np.concatenate([pos, nrm], axis=1).astype('f4')
                    vbo = ctx.buffer(data.tobytes())
                    ibo = ctx.buffer(idx.astype('u4').tobytes())
                    vao = ctx.vertex_array(prog, [(vbo, '3f 3f', 'in_pos', 'in_normal')], ibo)
                    entry = (s.geometry, vbo, ibo, vao)
                keep[key] = entry
                color = _check_color('%s: colour' % s.key, s.color)
                draw.append((s, entry[3], np.array(color + [1.0], dtype='f4').tobytes()))
            for key, entry in self._meshes.items():
                if keep.get(key) is not entry:
                    for obj in entry[:0:-1]:
                        obj.release()
            self._meshes = keep
            self._shapes = draw

    # --------------------------------------------------------------- render
    def render(self, camera_pose):
        """(rgb uint8 (height, width, 3) with row 0 at the top, depth float32 (height, width)
        in metres along the optical axis with inf for no return, or None without depth)."""
        if self._released:
            raise ModelError('ode_sim.render: render() on a released Renderer')
        cam = camera_pose.matrix()
        view = np.linalg.inv(cam)
        viewproj = (self._proj @ view).T.astype('f4').tobytes()       # column-major for GL
        models = [(s.world_pose().matrix().T.astype('f4').tobytes(), vao, col)
                  for s, vao, col in self._shapes]
        rgb = np.empty((self.height, self.width, 3), dtype=np.uint8)
        depth = None
        with _lock:
            ctx, prog = _context()
            self._fbo.use()
            ctx.enable_only(ctx.DEPTH_TEST)
            self._fbo.clear(*self._background, depth=1.0)
            prog['u_viewproj'].write(viewproj)
            prog['u_ambient'].value = tuple(self._ambient)
            prog['u_eye'].value = tuple(float(v) for v in cam[:3, 3])
            n, vec, dif, spe = self._lights
            prog['u_nlights'].value = n
            prog['u_light_vec'].write(vec)
            prog['u_light_diffuse'].write(dif)
            prog['u_light_specular'].write(spe)
            u_model, u_color = prog['u_model'], prog['u_color']
            for model, vao, col in models:
                u_model.write(model)
                u_color.write(col)
                vao.render()
            self._fbo.read_into(rgb, components=3, alignment=1)
            if self.depth:
                zbuf = np.empty((self.height, self.width), dtype=np.float32)
                self._fbo.read_into(zbuf, attachment=-1, alignment=1, dtype='f4')
        if self.depth:
            depth = self._linear_depth(zbuf)
        return rgb, depth

    def _linear_depth(self, zbuf):
        """Window depth in [0, 1] -> distance along the optical axis; 1 (cleared) -> inf."""
        n, f = self.near, self.far
        z = zbuf.astype(np.float64)
        ndc = 2.0 * z - 1.0
        with np.errstate(divide='ignore'):
            d = (2.0 * n * f) / ((f + n) - ndc * (f - n))
        d[(zbuf >= 1.0) | (d > f)] = np.inf
        return d.astype(np.float32)

    def release(self):
        """Free this renderer's GPU objects (the shared context stays)."""
        if self._released:
            return
        with _lock:
            for entry in self._meshes.values():
                for obj in entry[:0:-1]:
                    obj.release()
            self._meshes = {}
            self._shapes = []
            self._fbo.release()
            self._color_rb.release()
            self._depth_rb.release()
        self._released = True
