"""The process's one offscreen OpenGL context (moderngl on Mesa's EGL) and what lives in it:
the GL thread every GL call runs in, the shader programs (Gazebo's fixed-function lighting as
GLSL) and the textures shared by every Renderer (engine/render.py).

An EGL context is current in one thread only, so all GL work runs in one daemon thread
("ode_sim-gl"): `run(fn, *args)` hands fn over from any thread and waits for its result;
`post(fn)` hands it over without waiting (finalizers). `context()`, `program()` and
`texture()` are for the GL thread only.
"""
import math
import os
import queue
import sys
import threading

import numpy as np

from ode_sim.description.model import ModelError

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

_VERTEX_SHADER_UV = """
#version 330
uniform mat4 u_viewproj;
uniform mat4 u_model;
uniform vec2 u_uvscale;
in vec3 in_pos;
in vec3 in_normal;
in vec2 in_uv;
out vec3 v_world;
out vec3 v_normal;
out vec2 v_uv;
void main() {
    vec4 w = u_model * vec4(in_pos, 1.0);
    v_world = w.xyz;
    v_normal = mat3(u_model) * in_normal;
    v_uv = in_uv / u_uvscale;
    gl_Position = u_viewproj * w;
}
"""


def _fragment_shader(nlights, textured=False):
    """Per-pixel lighting, the light loop unrolled for `nlights` lights and branch-free (a
    loop over a uniform count with pow() costs llvmpipe ~3x as much); `textured`: the diffuse
    texture multiplies the material's ambient and diffuse colours."""
    head = ['#version 330', 'uniform vec4 u_color;', 'uniform vec3 u_ambient;',
            'uniform vec3 u_mat_ambient;', 'uniform vec3 u_mat_specular;',
            'uniform vec3 u_emissive;']
    if textured:
        head += ['uniform sampler2D u_tex;', 'in vec2 v_uv;']
    if nlights:
        head += ['uniform vec3 u_eye;',
                 # xyz: direction towards which the light shines (w = 0) or its position (w = 1)
                 'uniform vec4 u_light_vec[%d];' % nlights,
                 'uniform vec3 u_light_diffuse[%d];' % nlights,
                 'uniform vec3 u_light_specular[%d];' % nlights]
    head += ['in vec3 v_world;', 'in vec3 v_normal;', 'out vec4 f_color;', 'void main() {']
    if textured:
        head += ['    vec3 tex = texture(u_tex, v_uv).rgb;',
                 '    vec3 base = u_color.rgb * tex;',
                 '    vec3 c = u_ambient * u_mat_ambient * tex + u_emissive;']
    else:
        head += ['    vec3 base = u_color.rgb;',
                 '    vec3 c = u_ambient * u_mat_ambient + u_emissive;']
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
                 '             + (d > 0.0 ? s : 0.0) * u_mat_specular * u_light_specular[%d];' % i,
                 '    }']
    head += ['    f_color = vec4(min(c, vec3(1.0)), u_color.a);', '}', '']
    return '\n'.join(head)


_ctx = None
_programs = {}          # (number of lights, textured) -> moderngl.Program
_textures = {}          # (path, mtime) -> moderngl.Texture (GL thread), shared by renderers
_texture_data = {}      # (path, mtime) -> RGBA uint8 array, bottom row first, or None
_texture_warned = set()
_gl_thread = None
_gl_queue = queue.Queue()
_gl_start = threading.Lock()


def _worker():
    while True:
        fn, args, result, done = _gl_queue.get()
        try:
            result.append(fn(*args))
        except BaseException as e:  # noqa: BLE001 - handed back to the caller
            result.append(e)
            result.append(None)
        done.set()


def run(fn, *args):
    """Run fn(*args) in the GL thread and return its result (or raise its exception)."""
    global _gl_thread
    if threading.current_thread() is _gl_thread:
        return fn(*args)
    if _gl_thread is None:
        with _gl_start:
            if _gl_thread is None:
                t = threading.Thread(target=_worker, name='ode_sim-gl', daemon=True)
                t.start()
                _gl_thread = t
    result, done = [], threading.Event()
    _gl_queue.put((fn, args, result, done))
    done.wait()
    if len(result) == 2:
        raise result[0]
    return result[0]


def context():
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


def program(nlights, textured=False):
    """The shader program for `nlights` lights, with a texture or not (GL thread only)."""
    prog = _programs.get((nlights, textured))
    if prog is None:
        ctx = context()
        try:
            prog = ctx.program(vertex_shader=_VERTEX_SHADER_UV if textured else _VERTEX_SHADER,
                               fragment_shader=_fragment_shader(nlights, textured))
        except Exception as e:  # noqa: BLE001
            raise ModelError('ode_sim.render: shader compilation failed on %s: %s'
                             % (ctx.info.get('GL_RENDERER', '?'), e)) from None
        _programs[(nlights, textured)] = prog
    return prog


def texture_image(path):
    """(key, RGBA uint8 (h, w, 4) with the bottom row first, as GL wants it) of a texture
    file, decoded once per version with Pillow; (None, None) with a warning on stderr (once per
    file) when it cannot be read: the caller draws the plain colour."""
    try:
        key = (path, os.path.getmtime(path))
    except OSError as e:
        key, why = (path, None), e.strerror or str(e)
    else:
        if key in _texture_data:
            return (key, _texture_data[key]) if _texture_data[key] is not None else (None, None)
        why = None
        try:
            from PIL import Image
            with Image.open(path) as im:
                img = np.asarray(im.convert('RGBA'))[::-1].copy()
            if img.size == 0:
                raise ValueError('the image is empty')
        except ImportError:
            why = 'Pillow is not installed (Debian package python3-pil)'
        except Exception as e:  # noqa: BLE001 - PIL raises many kinds
            why = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
        _texture_data[key] = None if why else img
        if not why:
            return key, img
    if path not in _texture_warned:
        _texture_warned.add(path)
        sys.stderr.write('ode_sim.render: texture %s cannot be read (%s); drawn in its plain '
                         'colour\n' % (path, why))
    return None, None


def texture(ctx, key, img):
    tex = _textures.get(key)
    if tex is None:
        tex = ctx.texture((img.shape[1], img.shape[0]), 4, img.tobytes())
        tex.build_mipmaps()
        tex.filter = (ctx.LINEAR_MIPMAP_LINEAR, ctx.LINEAR)
        tex.repeat_x = tex.repeat_y = True
        _textures[key] = tex
    return tex


def gl_renderer():
    """'GL_RENDERER, GL_VERSION' of the shared context (creates it): e.g. 'llvmpipe ...'."""
    def info():
        i = context().info
        return '%s, OpenGL %s' % (i.get('GL_RENDERER', '?'), i.get('GL_VERSION', '?'))
    return run(info)


def started():
    """True once the GL thread runs."""
    return _gl_thread is not None


def post(fn):
    """Queue fn() for the GL thread without waiting for it (from finalizers)."""
    _gl_queue.put((fn, (), [], threading.Event()))
