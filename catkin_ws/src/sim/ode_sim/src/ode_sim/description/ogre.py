"""OGRE material scripts as Gazebo models carry them (materials/scripts/*.material).

Read: `material NAME [: PARENT]` (the parent's passes copied first), the first technique's
first pass: `ambient`, `diffuse`, `specular` (r g b [a] [shininess]), `emissive`
(`vertexcolour` is taken as white), and its first `texture_unit`: `texture FILE`, `scale SX SY`
(texture coordinates divided by it, as OGRE does); `filtering` and everything else (scroll,
rotate, env_map, shaders, further passes and units) is read over and not applied. Comments
`//` and `/* */`. A script that cannot be parsed gives one line naming file and line.
"""
import os
import re

from ode_sim.description.model import Material, ModelError

_TOKEN = re.compile(r'"[^"]*"|\{|\}|[^\s{}"]+|\n')


def _tokens(text):
    text = re.sub(r'/\*.*?\*/', lambda m: '\n' * m.group(0).count('\n'), text, flags=re.S)
    out, line = [], 1
    for raw in text.split('\n'):
        raw = raw.split('//', 1)[0]
        toks = [t.strip('"') if t.startswith('"') else t
                for t in _TOKEN.findall(raw) if t != '\n']
        out.append((line, toks))
        line += 1
    return out


def _nums(vals, n, path, line, key):
    try:
        v = [float(x) for x in vals[:n]]
    except ValueError:
        raise ModelError('%s:%d: %s expects numbers, got %r' % (path, line, key, ' '.join(vals)))
    return v


class _Block:
    def __init__(self, kind, args, line):
        self.kind, self.args, self.line = kind, args, line
        self.props = []          # (key, values, line)
        self.children = []


def _parse_blocks_lines(path, text):
    root = _Block('', [], 0)
    stack = [root]
    lines = _tokens(text)
    pending = None
    for line, toks in lines:
        if pending is not None and toks and toks[0] != '{':
            stack[-1].props.append((pending[0][0], pending[0][1:], pending[1]))
            pending = None
        i = 0
        while i < len(toks):
            t = toks[i]
            if t == '{':
                if pending is None:
                    raise ModelError('%s:%d: "{" without a block name' % (path, line))
                blk = _Block(pending[0][0], pending[0][1:], pending[1])
                stack[-1].children.append(blk)
                stack.append(blk)
                pending = None
                i += 1
            elif t == '}':
                if pending is not None:
                    stack[-1].props.append((pending[0][0], pending[0][1:], pending[1]))
                    pending = None
                if len(stack) == 1:
                    raise ModelError('%s:%d: "}" without an open block' % (path, line))
                stack.pop()
                i += 1
            else:
                rest = []
                while i < len(toks) and toks[i] not in ('{', '}'):
                    rest.append(toks[i])
                    i += 1
                if pending is not None:
                    stack[-1].props.append((pending[0][0], pending[0][1:], pending[1]))
                pending = (rest, line)
    if pending is not None:
        stack[-1].props.append((pending[0][0], pending[0][1:], pending[1]))
    if len(stack) != 1:
        raise ModelError('%s:%d: block "%s" is not closed (missing "}")'
                         % (path, stack[-1].line, ' '.join([stack[-1].kind] + stack[-1].args)))
    return root


def _first(block, kind):
    for c in block.children:
        if c.kind == kind:
            return c
    return None


def _material_fields(path, blk):
    """{field: value} of a material block's first technique / pass / texture_unit."""
    out = {}
    tech = _first(blk, 'technique')
    p = _first(tech, 'pass') if tech is not None else None
    if p is None:
        return out
    for key, vals, line in p.props:
        if key in ('ambient', 'diffuse', 'specular', 'emissive'):
            if vals and vals[0] == 'vertexcolour':
                out[key] = (1.0, 1.0, 1.0, 1.0)
                continue
            v = _nums(vals, 5 if key == 'specular' else 4, path, line, key)
            if len(v) < 3:
                raise ModelError('%s:%d: %s needs r g b [a], got %r'
                                 % (path, line, key, ' '.join(vals)))
            rgba = tuple(v[:3]) + ((v[3],) if len(v) > 3 else (1.0,))
            out[key] = rgba
    tu = _first(p, 'texture_unit')
    if tu is not None:
        for key, vals, line in tu.props:
            if key == 'texture' and vals:
                out['texture'] = vals[0]
            elif key == 'scale':
                v = _nums(vals, 2, path, line, 'scale')
                if len(v) == 2 and v[0] != 0 and v[1] != 0:
                    out['uv_scale'] = (v[0], v[1])
    return out


def parse_scripts(files):
    """{material name: (fields, script path)} of the given .material files, parents resolved."""
    raw = {}
    for path in files:
        try:
            with open(path, encoding='utf-8', errors='replace') as f:
                text = f.read()
        except OSError as e:
            raise ModelError('%s: cannot read: %s' % (path, e.strerror or e))
        root = _parse_blocks_lines(path, text)
        for blk in root.children:
            if blk.kind != 'material' or not blk.args:
                continue
            name = blk.args[0]
            parent = blk.args[2] if len(blk.args) >= 3 and blk.args[1] == ':' else None
            if parent is None and len(blk.args) >= 2 and blk.args[1].startswith(':'):
                parent = blk.args[1][1:] or (blk.args[2] if len(blk.args) > 2 else None)
            raw[name] = (parent, _material_fields(path, blk), path)
    out = {}

    def resolve(name, seen=()):
        if name in out:
            return out[name]
        parent, fields, path = raw[name]
        merged = {}
        if parent and parent in raw and parent not in seen:
            merged.update(resolve(parent, seen + (name,))[0])
        merged.update(fields)
        out[name] = (merged, path)
        return out[name]

    for name in raw:
        resolve(name)
    return out


def script_files(dirs_or_files):
    """The .material files of these directories (sorted) and files, in order."""
    out = []
    for p in dirs_or_files:
        if os.path.isdir(p):
            out += [os.path.join(p, f) for f in sorted(os.listdir(p)) if f.endswith('.material')]
        elif p.endswith('.material') and os.path.isfile(p):
            out.append(p)
    return out


def to_material(name, fields, script, search_dirs):
    """A model.Material of a parsed script material; (material, warning or None). The texture
    is looked up beside the script, in ../textures and in `search_dirs`."""
    d = fields.get('diffuse', (1.0, 1.0, 1.0, 1.0))
    mat = Material(name=name, diffuse=tuple(d), ambient=fields.get('ambient'),
                   emissive=tuple(fields.get('emissive', (0, 0, 0, 1))[:3]),
                   specular=tuple(fields.get('specular', (0, 0, 0, 1))[:3]),
                   opacity=float(d[3]), uv_scale=tuple(fields.get('uv_scale', (1.0, 1.0))),
                   source=script)
    tex = fields.get('texture')
    if not tex:
        return mat, None
    here = os.path.dirname(script)
    cands = [os.path.join(here, tex), os.path.join(os.path.dirname(here), 'textures', tex)]
    cands += [os.path.join(d_, tex) for d_ in search_dirs if os.path.isdir(d_)]
    for c in cands:
        if os.path.isfile(c):
            mat.texture = os.path.abspath(c)
            return mat, None
    return mat, ('%s: material %r: texture %r not found (searched: %s); drawn in its plain '
                 'colour' % (script, name, tex, ', '.join(cands)))
