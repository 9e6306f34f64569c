"""Camera images by real OpenGL, offscreen: moderngl on Mesa's EGL (llvmpipe works, no display).

One EGL context per process, created on first use and shared by every Renderer (each has its
own framebuffer of its own size). An EGL context is current in one thread only, so all GL work
runs in one daemon thread of this module ("ode_sim-gl"); Renderer methods may be called from
any thread (they hand the GL part over and wait for it).

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
little Blinn-Phong specular; back faces are culled as in Gazebo (OGRE), so a camera inside its
own link's box sees out of it (the textbook's camera sits inside a 5 cm cube with a 2 cm near
clip); triangles are wound counter-clockwise seen from outside; no shadows, colours are opaque
(alpha ignored).
"""
import math
import queue
import threading

import numpy as np

from ode_sim.description.model import ModelError
from ode_sim.engine.tessellate import tessellate

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



def _fragment_shader(nlights):
    """Per-pixel lighting, the light loop unrolled for `nlights` lights and branch-free (a
    loop over a uniform count with pow() costs llvmpipe ~3x as much)."""
    head = ['#version 330', 'uniform vec4 u_color;', 'uniform vec3 u_ambient;']
    if nlights:
        head += ['uniform vec3 u_eye;',
                 # xyz: direction towards which the light shines (w = 0) or its position (w = 1)
                 'uniform vec4 u_light_vec[%d];' % nlights,
                 'uniform vec3 u_light_diffuse[%d];' % nlights,
                 'uniform vec3 u_light_specular[%d];' % nlights]
    head += ['in vec3 v_world;', 'in vec3 v_normal;', 'out vec4 f_color;', 'void main() {',
             '    vec3 base = u_color.rgb;', '    vec3 c = u_ambient * base;']
    if nlights:
        head += ['    vec3 view = normalize(u_eye - v_world);',
                 '    vec3 n = normalize(v_normal);',
                 '    n = dot(n, view) < 0.0 ? -n : n;         // both sides lit']
    squarings = int(round(math.log2(SHININESS)))
    for i in range(nlights):
        head += ['    {',
                 '        vec4 lv = u_light_vec[%d];' % i,
                 '        vec3 l = normalize(mix(-lv.xyz, lv.xyz - v_world, lv.w));',
                 '        float d = max(dot(n, l), 0.0);',
                 '        float s = max(dot(n, normalize(l + view)), 0.0);',
                 '        ' + ' '.join(['s *= s;'] * squarings) + '   // s^%d' % 2 ** squarings,
                 '        c += d * u_light_diffuse[%d] * base' % i,
                 '             + (d > 0.0 ? %f * s : 0.0) * u_light_specular[%d];' % (SPECULAR, i),
                 '    }']
    head += ['    f_color = vec4(min(c, vec3(1.0)), 1.0);', '}', '']
    return '\n'.join(head)


_ctx = None
_programs = {}          # number of lights -> moderngl.Program
_gl_thread = None
_gl_queue = queue.Queue()
_gl_start = threading.Lock()


def _gl_worker():
    while True:
        fn, args, result, done = _gl_queue.get()
        try:
            result.append(fn(*args))
        except BaseException as e:  # noqa: BLE001 - handed back to the caller
            result.append(e)
            result.append(None)
        done.set()


def _gl(fn, *args):
    """Run fn(*args) in the GL thread and return its result (or raise its exception)."""
    global _gl_thread
    if threading.current_thread() is _gl_thread:
        return fn(*args)
    if _gl_thread is None:
        with _gl_start:
            if _gl_thread is None:
                t = threading.Thread(target=_gl_worker, name='ode_sim-gl', daemon=True)
                t.start()
                _gl_thread = t
    result, done = [], threading.Event()
    _gl_queue.put((fn, args, result, done))
    done.wait()
    if len(result) == 2:
        raise result[0]
    return result[0]


def _context():
    """The process's EGL context, created on first call (GL thread only)."""
    global _ctx
    if _ctx is None:
        try:
            import moderngl
        except ImportError as e:
            raise ModelError('ode_sim.render: cannot import moderngl (%s): install the Debian '
                             'package python3-moderngl' % e) from None
        try:
            _ctx = moderngl.create_standalone_context(backend='egl', require=330)
        except Exception as e:  # noqa: BLE001 - moderngl raises plain Exception
            raise ModelError('ode_sim.render: cannot create an offscreen OpenGL 3.3 context '
                             'through EGL (%s): install libegl1, libegl-mesa0 and '
                             'libgl1-mesa-dri' % str(e).strip().splitlines()[0]) from None
    return _ctx


def _program(nlights):
    """The shader program for `nlights` lights (GL thread only)."""
    prog = _programs.get(nlights)
    if prog is None:
        ctx = _context()
        try:
            prog = ctx.program(vertex_shader=_VERTEX_SHADER,
                               fragment_shader=_fragment_shader(nlights))
        except Exception as e:  # noqa: BLE001
            raise ModelError('ode_sim.render: shader compilation failed on %s: %s'
                             % (ctx.info.get('GL_RENDERER', '?'), e)) from None
        _programs[nlights] = prog
    return prog


def gl_renderer():
    """'GL_RENDERER, GL_VERSION' of the shared context (creates it): e.g. 'llvmpipe ...'."""
    def info():
        i = _context().info
        return '%s, OpenGL %s' % (i.get('GL_RENDERER', '?'), i.get('GL_VERSION', '?'))
    return _gl(info)


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
        self._meshes = {}                  # id(geometry) -> _Mesh
        self._prog = None
        self._released = False
        self._color_rb = self._depth_rb = self._fbo = None
        _gl(self._gl_create)
        self.set_scene([])

    def _gl_create(self):
        ctx = _context()
        try:
            self._color_rb = ctx.renderbuffer((self.width, self.height), components=4)
            self._depth_rb = ctx.depth_renderbuffer((self.width, self.height))
            self._fbo = ctx.framebuffer(color_attachments=[self._color_rb],
                                        depth_attachment=self._depth_rb)
        except Exception as e:  # noqa: BLE001 - moderngl raises plain Exception
            raise ModelError('ode_sim.render: cannot create a %dx%d framebuffer: %s'
                             % (self.width, self.height, e)) from None

    # ---------------------------------------------------------------- scene
    def set_scene(self, shapes, lights=(), ambient=(0.4, 0.4, 0.4, 1), background=(0.7, 0.7, 0.7, 1)):
        """Shapes (ShapeInstance visuals) and lights (model.Light) to draw from now on.

        GPU meshes are cached per geometry object (by identity): calling again after models
        were added or removed uploads only the new geometries and frees the unused ones.
        Only the first MAX_LIGHTS lights are used; point and spot lights shine from their
        position in all directions without falloff.
        """
        amb = _check_color('scene ambient', ambient)
        bg = _check_color('scene background', background)
        lights = list(lights)[:MAX_LIGHTS]
        vec, dif, spe = [], [], []
        for light in lights:
            if light.type == 'directional':
                d = np.asarray(light.direction, dtype=float)
                n = np.linalg.norm(d) if d.shape == (3,) else 0.0
                if not np.isfinite(n) or n == 0:
                    raise ModelError('ode_sim.render: light %r: direction %r is not a 3D '
                                     'direction' % (light.name, light.direction))
                vec += list(d / n) + [0.0]
            else:
                vec += list(light.pose.p) + [1.0]
            dif += _check_color('light %r diffuse' % light.name, light.diffuse)
            spe += _check_color('light %r specular' % light.name, light.specular)
        lights_u = (len(lights), np.array(vec, dtype='f4').tobytes(),
                    np.array(dif, dtype='f4').tobytes(), np.array(spe, dtype='f4').tobytes())
        # CPU side first (bad input raises before anything changes), then the upload
        draw, new = [], {}
        for sh in shapes:
            key = id(sh.geometry)
            color = _check_color('%s: colour' % sh.key, sh.color)
            old = self._meshes.get(key)
            if key not in new and (old is None or old.geometry is not sh.geometry):
                pos, nrm, idx = tessellate(sh.geometry, sh.key)
                new[key] = (sh.geometry, np.concatenate([pos, nrm], axis=1).astype('f4'),
                            idx.astype('u4'))
            draw.append((sh, key, np.array(color + [1.0], dtype='f4').tobytes()))
        _gl(self._gl_set_scene, draw, new, lights_u)
        self._ambient, self._background, self._lights = amb, tuple(bg) + (1.0,), lights_u

    def _gl_set_scene(self, draw, new, lights_u):
        ctx = _context()
        prog = _program(lights_u[0])
        keep = {}
        for key, (geometry, data, idx) in new.items():
            keep[key] = _Mesh(ctx, geometry, data, idx)
        for _, key, _ in draw:
            if key not in keep:
                keep[key] = self._meshes[key]
        for key, mesh in self._meshes.items():
            if keep.get(key) is not mesh:
                mesh.release()
        self._meshes = keep
        self._prog = prog
        self._shapes = [(sh, keep[key].vao(ctx, prog), col) for sh, key, col in draw
                        if keep[key].count]

    # --------------------------------------------------------------- render
    def render(self, camera_pose):
        """(rgb uint8 (height, width, 3) with row 0 at the top, depth float32 (height, width)
        in metres along the optical axis with inf for no return, or None without depth)."""
        if self._released:
            raise ModelError('ode_sim.render: render() on a released Renderer')
        cam = camera_pose.matrix()
        viewproj = (self._proj @ np.linalg.inv(cam)).T.astype('f4').tobytes()  # column-major
        models = [(s.world_pose().matrix().T.astype('f4').tobytes(), vao, col)
                  for s, vao, col in self._shapes]
        rgb = np.empty((self.height, self.width, 3), dtype=np.uint8)
        zbuf = np.empty((self.height, self.width), dtype=np.float32) if self.depth else None
        _gl(self._gl_render, viewproj, tuple(float(v) for v in cam[:3, 3]), models, rgb, zbuf)
        return rgb, (self._linear_depth(zbuf) if self.depth else None)

    def _gl_render(self, viewproj, eye, models, rgb, zbuf):
        ctx, prog = _context(), self._prog
        self._fbo.use()
        ctx.enable_only(ctx.DEPTH_TEST | ctx.CULL_FACE)
        ctx.front_face = 'cw'          # the projection flips Y (image rows top first)
        self._fbo.clear(*self._background, depth=1.0)
        prog['u_viewproj'].write(viewproj)
        prog['u_ambient'].value = tuple(self._ambient)
        n, vec, dif, spe = self._lights
        if n:
            prog['u_eye'].value = eye
            prog['u_light_vec'].write(vec)
            prog['u_light_diffuse'].write(dif)
            prog['u_light_specular'].write(spe)
        u_model, u_color = prog['u_model'], prog['u_color']
        for model, vao, col in models:
            u_model.write(model)
            u_color.write(col)
            vao.render()
        self._fbo.read_into(rgb, components=3, alignment=1)
        if zbuf is not None:
            self._fbo.read_into(zbuf, attachment=-1, alignment=1, dtype='f4')

    def _linear_depth(self, zbuf):
        """Window depth z in [0, 1] -> distance along the optical axis, n f / (f - z (f - n)),
        in place (float32); z = 1 (cleared: no surface) or beyond far -> inf."""
        n, f = self.near, self.far
        miss = zbuf >= 1.0
        d = zbuf
        d *= -(f - n)
        d += f
        with np.errstate(divide='ignore'):
            np.divide(n * f, d, out=d)
        d[miss | (d > f)] = np.inf
        return d

    def release(self):
        """Free this renderer's GPU objects (the shared context stays)."""
        if self._released:
            return
        self._released = True
        _gl(self._gl_release)

    def _gl_release(self):
        for mesh in self._meshes.values():
            mesh.release()
        self._meshes = {}
        self._shapes = []
        for obj in (self._fbo, self._color_rb, self._depth_rb):
            if obj is not None:
                obj.release()
        self._fbo = self._color_rb = self._depth_rb = None

    def __del__(self):
        try:
            if not self._released and _gl_thread is not None:
                self._released = True
                _gl_queue.put((self._gl_release, (), [], threading.Event()))
        except Exception:  # noqa: BLE001 - interpreter shutdown
            pass


class _Mesh:
    """GPU buffers of one geometry and its vertex arrays, one per shader program."""

    def __init__(self, ctx, geometry, data, idx):
        self.geometry = geometry
        self.count = len(idx)
        self.vbo = ctx.buffer(data.tobytes()) if self.count else None
        self.ibo = ctx.buffer(idx.tobytes()) if self.count else None
        self.vaos = {}

    def vao(self, ctx, prog):
        vao = self.vaos.get(id(prog))
        if vao is None:
            # a program that does not use the normals (depth only, no lights) has no in_normal:
            # skip those 12 bytes (moderngl >= 5.9, Debian 13, refuses an unknown attribute)
            if prog.get('in_normal', None) is None:
                content = [(self.vbo, '3f 12x', 'in_pos')]
            else:
                content = [(self.vbo, '3f 3f', 'in_pos', 'in_normal')]
            vao = ctx.vertex_array(prog, content, self.ibo)
            self.vaos[id(prog)] = vao
        return vao

    def release(self):
        for vao in self.vaos.values():
            vao.release()
        self.vaos = {}
        for buf in (self.ibo, self.vbo):
            if buf is not None:
                buf.release()
        self.ibo = self.vbo = None
