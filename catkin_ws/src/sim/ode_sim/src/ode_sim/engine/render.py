"""Camera images by real OpenGL, offscreen: moderngl on Mesa's EGL (llvmpipe works, no display).

One EGL context per process, created on first use and shared by every Renderer (each has its
own framebuffer of its own size). An EGL context is current in one thread only, so all GL work
runs in one daemon thread (engine/gl.py, "ode_sim-gl"); Renderer methods may be called from
any thread (they hand the GL part over and wait for it).

Camera convention (Gazebo's): the camera frame looks along +X, +Z is up, +Y is left. The image
is a pinhole projection with square pixels: focal length f = width / (2 tan(hfov / 2)) pixels,
principal point exactly at the image centre (pixel-centre coordinates (width-1)/2,
(height-1)/2 when pixel 0 is centred on 0), as Gazebo renders it. `camera_info_matrix`
(engine/camera.py) gives the K and P matrices that gazebo_ros_camera_utils publishes by
default; note that those put cx, cy at (width+1)/2, (height+1)/2, one pixel right/down of the
true centre — Gazebo's long-standing default, kept for compatibility.

Depth: distance along the optical axis (the camera's X) in metres, float32; +inf where nothing
is hit or the surface is beyond `far` (also below `near`, things are clipped away). Gazebo's
depth camera plugin (gazebo_ros_openni_kinect) publishes such pixels as NaN in its 32FC1
depth image (everything outside (pointCloudCutoff, pointCloudCutoffMax)); the ROS-publishing
layer maps inf to NaN, this module keeps inf so that comparisons stay meaningful.

Lighting (OGRE's fixed-function pass as Gazebo uses it): scene ambient x material ambient, plus
per light a Lambert term (light diffuse x material diffuse) and a Blinn-Phong specular (light
specular x material specular), plus the material's emissive; a texture (the material's diffuse
texture, OGRE's texture_unit) multiplies ambient and diffuse (colour_op modulate); back faces
are culled as in Gazebo (OGRE), so a camera inside its own link's box sees out of it (the
textbook's camera sits inside a 5 cm cube with a 2 cm near clip); triangles are wound
counter-clockwise seen from outside; no shadows. A shape with only a colour (URDF, SDF
<diffuse>) uses it as ambient and diffuse with a 0.2 specular. Materials with opacity < 1 are
drawn after the opaque ones, blended. Mesh files' parts (description/mesh.py) are drawn with
their own normals, texture coordinates and the file's materials unless the visual has its own
material. Texture images are read with Pillow (one decode per file and version); one that
cannot be read is drawn in its material's plain colour, with a warning on stderr.
"""
import math

import numpy as np

from ode_sim.description.model import ModelError
from ode_sim.engine import gl
from ode_sim.engine.camera import camera_info_matrix, focal_length  # noqa: F401 (re-exported)
from ode_sim.engine.tessellate import tessellate, uv_of

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
        self._progs = {}
        self._released = False
        self._color_rb = self._depth_rb = self._fbo = None
        gl.run(self._gl_create)
        self.set_scene([])

    def _gl_create(self):
        ctx = gl.context()
        try:
            self._color_rb = ctx.renderbuffer((self.width, self.height), components=4)
            self._depth_rb = ctx.depth_renderbuffer((self.width, self.height))
            self._fbo = ctx.framebuffer(color_attachments=[self._color_rb],
                                        depth_attachment=self._depth_rb)
        except Exception as e:  # noqa: BLE001 - moderngl raises plain Exception
            raise ModelError('ode_sim.render: cannot create a %dx%d framebuffer: %s'
                             % (self.width, self.height, e)) from None

    # ---------------------------------------------------------------- scene
    def set_scene(self, shapes, lights=(), ambient=(0.4, 0.4, 0.4, 1),
                  background=(0.7, 0.7, 0.7, 1)):
        """Shapes (ShapeInstance visuals) and lights (model.Light) to draw from now on.

        GPU meshes are cached per geometry object (by identity) and part: calling again after
        models were added or removed uploads only the new geometries and frees the unused ones.
        Only the first MAX_LIGHTS (engine/gl.py) lights are used; point and spot lights shine
        from their position in all directions without falloff.
        """
        amb = _check_color('scene ambient', ambient)
        bg = _check_color('scene background', background)
        lights = list(lights)[:gl.MAX_LIGHTS]
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
            color = _check_color('%s: colour' % sh.key, sh.color)
            own = getattr(sh, 'material', None)
            g = sh.geometry
            parts = g.parts if g.kind == 'mesh' and getattr(g, 'parts', None) else [None]
            for index, part in enumerate(parts):
                mat = own or (part.material if part is not None else None)
                uniforms, tex_key, tex_img = _uniforms(sh.key, mat, color)
                textured = tex_key is not None
                key = (id(g), index, textured)
                old = self._meshes.get(key)
                if key not in new and (old is None or old.geometry is not g):
                    if part is None:
                        pos, nrm, idx = tessellate(g, sh.key)
                        uv = uv_of(g, pos, nrm) if textured else None
                    else:
                        pos, nrm, idx = part.positions, part.normals, part.faces
                        uv = part.uvs if textured else None
                        if textured and uv is None:
                            uv = np.zeros((len(pos), 2), dtype='f4')
                    cols = [pos, nrm] + ([uv] if textured else [])
                    new[key] = (g, np.concatenate(cols, axis=1).astype('f4'),
                                np.asarray(idx).astype('u4'), textured)
                draw.append((sh, key, uniforms, tex_key, tex_img))
        gl.run(self._gl_set_scene, draw, new, lights_u)
        self._ambient, self._background, self._lights = amb, tuple(bg) + (1.0,), lights_u

    def _gl_set_scene(self, draw, new, lights_u):
        ctx = gl.context()
        progs = {False: gl.program(lights_u[0], False), True: gl.program(lights_u[0], True)}
        keep = {}
        for key, (geometry, data, idx, textured) in new.items():
            keep[key] = _Mesh(ctx, geometry, data, idx, textured)
        for _, key, _, _, _ in draw:
            if key not in keep:
                keep[key] = self._meshes[key]
        for key, mesh in self._meshes.items():
            if keep.get(key) is not mesh:
                mesh.release()
        self._meshes = keep
        self._progs = progs
        items = []
        for sh, key, uniforms, tex_key, tex_img in draw:
            mesh = keep[key]
            if not mesh.count:
                continue
            textured = tex_key is not None
            tex = gl.texture(ctx, tex_key, tex_img) if textured else None
            items.append((sh, mesh.vao(ctx, progs[textured]), uniforms, tex, textured))
        # opaque plain, opaque textured, then the transparent ones (blended)
        items.sort(key=lambda it: (it[2][-1] < 1.0, it[4]))
        self._shapes = items

    # --------------------------------------------------------------- render
    def render(self, camera_pose):
        """(rgb uint8 (height, width, 3) with row 0 at the top, depth float32 (height, width)
        in metres along the optical axis with inf for no return, or None without depth)."""
        if self._released:
            raise ModelError('ode_sim.render: render() on a released Renderer')
        cam = camera_pose.matrix()
        viewproj = (self._proj @ np.linalg.inv(cam)).T.astype('f4').tobytes()  # column-major
        models = [(s.world_pose().matrix().T.astype('f4').tobytes(), vao, u, tex, textured)
                  for s, vao, u, tex, textured in self._shapes]
        rgb = np.empty((self.height, self.width, 3), dtype=np.uint8)
        zbuf = np.empty((self.height, self.width), dtype=np.float32) if self.depth else None
        gl.run(self._gl_render, viewproj, tuple(float(v) for v in cam[:3, 3]), models, rgb, zbuf)
        return rgb, (self._linear_depth(zbuf) if self.depth else None)

    def _gl_render(self, viewproj, eye, models, rgb, zbuf):
        self._gl_draw(viewproj, eye, models)
        self._fbo.read_into(rgb, components=3, alignment=1)
        if zbuf is not None:
            self._fbo.read_into(zbuf, attachment=-1, alignment=1, dtype='f4')

    def _gl_draw(self, viewproj, eye, models, clear=True):
        """Draw `models` (render()'s list) into this renderer's framebuffer (GL thread), on
        the sky colour or (clear False) over what the framebuffer holds."""
        ctx = gl.context()
        self._fbo.use()
        ctx.enable_only(ctx.DEPTH_TEST | ctx.CULL_FACE)
        ctx.front_face = 'cw'          # the projection flips Y (image rows top first)
        if clear:
            self._fbo.clear(*self._background, depth=1.0)
        n, vec, dif, spe = self._lights
        handles = {}
        for textured, prog in self._progs.items():
            prog['u_viewproj'].write(viewproj)
            prog['u_ambient'].value = tuple(self._ambient)
            if n:
                prog['u_eye'].value = eye
                prog['u_light_vec'].write(vec)
                prog['u_light_diffuse'].write(dif)
                prog['u_light_specular'].write(spe)
            handles[textured] = tuple(prog.get(u, None) for u in (
                'u_model', 'u_color', 'u_mat_ambient', 'u_mat_specular', 'u_emissive',
                'u_uvscale'))
        blending = False
        for model, vao, (col, mamb, mspec, emis, uvs, alpha), tex, textured in models:
            u_model, u_color, u_amb, u_spec, u_emis, u_uvs = handles[textured]
            if alpha < 1.0 and not blending:
                ctx.enable(ctx.BLEND)
                ctx.blend_func = ctx.SRC_ALPHA, ctx.ONE_MINUS_SRC_ALPHA
                blending = True
            u_model.write(model)
            u_color.write(col)
            if u_amb is not None:
                u_amb.write(mamb)
            if u_spec is not None:
                u_spec.write(mspec)
            if u_emis is not None:
                u_emis.write(emis)
            if textured:
                if u_uvs is not None:
                    u_uvs.write(uvs)
                tex.use(0)
            vao.render()
        if blending:
            ctx.disable(ctx.BLEND)

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
        gl.run(self._gl_release)

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
            if not self._released and gl.started():
                self._released = True
                gl.post(self._gl_release)
        except Exception:  # noqa: BLE001 - interpreter shutdown
            pass


class _Mesh:
    """GPU buffers of one geometry part and its vertex arrays, one per shader program."""

    def __init__(self, ctx, geometry, data, idx, textured=False):
        self.geometry = geometry
        self.textured = textured
        self.count = len(idx)
        self.vbo = ctx.buffer(data.tobytes()) if self.count else None
        self.ibo = ctx.buffer(np.ascontiguousarray(idx).tobytes()) if self.count else None
        self.vaos = {}

    def vao(self, ctx, prog):
        vao = self.vaos.get(id(prog))
        if vao is None:
            # a program that does not use the normals (depth only, no lights) has no in_normal:
            # skip those 12 bytes (moderngl >= 5.9, Debian 13, refuses an unknown attribute)
            uv = ' 8x' if self.textured else ''
            if prog.get('in_normal', None) is None:
                fmt, names = '3f 12x', ['in_pos']
            else:
                fmt, names = '3f 3f', ['in_pos', 'in_normal']
            if self.textured:
                if prog.get('in_uv', None) is not None:
                    fmt, names, uv = fmt + ' 2f', names + ['in_uv'], ''
            content = [(self.vbo, fmt + uv, *names)]
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


def _uniforms(where, mat, color):
    """((diffuse rgba, ambient rgb, specular rgb, emissive rgb, uv scale as f4 bytes, opacity),
    texture key, texture image) of a material, or of a plain colour when `mat` is None."""
    tex_key = tex_img = None
    if mat is None:
        diffuse = list(color) + [1.0]
        ambient, specular, emissive, uvs = color, [gl.SPECULAR] * 3, [0.0] * 3, (1.0, 1.0)
    else:
        d = _check_color('%s: material %r diffuse' % (where, mat.name), mat.diffuse)
        opacity = float(mat.opacity)
        if not 0.0 <= opacity <= 1.0:
            opacity = 1.0
        diffuse = d + [opacity]
        ambient = d if mat.ambient is None else \
            _check_color('%s: material %r ambient' % (where, mat.name), mat.ambient)
        specular = _check_color('%s: material %r specular' % (where, mat.name), mat.specular)
        emissive = _check_color('%s: material %r emissive' % (where, mat.name), mat.emissive)
        uvs = tuple(float(v) for v in mat.uv_scale)
        if mat.texture:
            tex_key, tex_img = gl.texture_image(mat.texture)
    f4 = lambda v: np.array(v, dtype='f4').tobytes()  # noqa: E731
    return (f4(diffuse), f4(ambient), f4(specular), f4(emissive), f4(uvs), diffuse[3]), \
        tex_key, tex_img
