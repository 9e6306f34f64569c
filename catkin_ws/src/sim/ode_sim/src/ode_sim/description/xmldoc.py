"""XML with line numbers and the parse context the SDF and URDF readers share: every error is
one line `FILE:LINE: what` (ModelError)."""
import math
import xml.parsers.expat
import xml.etree.ElementTree as ET

from ode_sim.description.model import ModelError
from ode_sim.description.transforms import Pose


# ------------------------------------------------------------------------------------------
# XML with line numbers

class XmlDoc:
    """An ElementTree root plus the source line of every element."""

    def __init__(self, root, lines, source):
        self.root = root
        self.lines = lines
        self.source = source

    def line(self, elem):
        return self.lines.get(id(elem), 0)

    def where(self, elem):
        n = self.line(elem)
        return '%s:%d' % (self.source, n) if n else self.source

    def error(self, elem, msg):
        return ModelError('%s: %s' % (self.where(elem), msg))


def parse_xml(text, source):
    """Parse XML text; malformed -> ModelError 'SOURCE:LINE: malformed XML: ...'."""
    if isinstance(text, bytes):
        data = text
    else:
        data = (text or '').encode('utf-8')
        # the text is already decoded: drop a declared encoding other than UTF-8
        if data.lstrip().startswith(b'<?xml'):
            end = data.find(b'?>')
            if end > 0:
                decl = data[:end]
                if b'encoding' in decl and b'utf-8' not in decl.lower():
                    data = b'<?xml version="1.0"?>' + data[end + 2:]
    lines = {}
    stack = []
    result = []
    text_parts = {}
    parser = xml.parsers.expat.ParserCreate()

    def start(tag, attrs):
        elem = ET.Element(tag, attrs)
        lines[id(elem)] = parser.CurrentLineNumber
        if stack:
            stack[-1].append(elem)
        else:
            result.append(elem)
        stack.append(elem)

    def end(tag):
        elem = stack.pop()
        parts = text_parts.pop(id(elem), None)
        if parts:
            elem.text = ''.join(parts)

    def chars(data_):
        if stack:
            elem = stack[-1]
            if len(elem):       # text after a child: its tail
                child = elem[-1]
                child.tail = (child.tail or '') + data_
            else:
                text_parts.setdefault(id(elem), []).append(data_)

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    parser.CharacterDataHandler = chars
    parser.buffer_text = True
    try:
        parser.Parse(data, True)
    except xml.parsers.expat.ExpatError as e:
        raise ModelError('%s:%d: malformed XML: %s (column %d)'
                         % (source, e.lineno, xml.parsers.expat.ErrorString(e.code),
                            e.offset + 1))
    if not result:
        raise ModelError('%s: malformed XML: no root element' % source)
    # keep the elements alive as long as the doc (ids stay unique)
    doc = XmlDoc(result[0], lines, source)
    doc._keep = list(result[0].iter())
    return doc


# ------------------------------------------------------------------------------------------
# small value parsers

def text_of(elem, tag, default=None):
    child = elem.find(tag) if elem is not None else None
    if child is None or child.text is None or not child.text.strip():
        return default
    return child.text.strip()


class ParseContext:
    def __init__(self, doc, paths, base_dir, warnings, version):
        self.doc = doc
        self.paths = paths
        self.base_dir = base_dir
        self.warnings = warnings
        self.version = version

    @property
    def v14(self):
        return self.version < (1, 5)

    def err(self, elem, msg):
        return self.doc.error(elem, msg)

    def warn(self, elem, msg):
        self.warnings.append('%s: %s' % (self.doc.where(elem), msg))

    def floats(self, elem, tag, n, default=None):
        child = elem.find(tag)
        if child is None or child.text is None or not child.text.strip():
            if default is None:
                raise self.err(elem, '<%s> needs <%s> (%d number%s)'
                               % (elem.tag, tag, n, 's' if n > 1 else ''))
            return tuple(default) if n > 1 else default
        try:
            vals = [float(v) for v in child.text.split()]
        except ValueError:
            raise self.err(child, '<%s> must be %d number%s, got %r'
                           % (tag, n, 's' if n > 1 else '', child.text.strip()))
        if len(vals) != n or not all(math.isfinite(v) for v in vals):
            raise self.err(child, '<%s> must be %d finite number%s, got %r'
                           % (tag, n, 's' if n > 1 else '', child.text.strip()))
        return tuple(vals) if n > 1 else vals[0]

    def num(self, elem, tag, default):
        return self.floats(elem, tag, 1, default)

    def integer(self, elem, tag, default):
        v = self.floats(elem, tag, 1, float(default))
        if v != int(v):
            raise self.err(elem.find(tag), '<%s> must be an integer, got %r'
                           % (tag, elem.find(tag).text.strip()))
        return int(v)

    def boolean(self, elem, tag, default):
        child = elem.find(tag)
        if child is None or child.text is None or not child.text.strip():
            return default
        t = child.text.strip().lower()
        if t in ('1', 'true', 'yes'):
            return True
        if t in ('0', 'false', 'no'):
            return False
        raise self.err(child, '<%s> must be true/false/1/0, got %r' % (tag, child.text.strip()))

    def color(self, elem, tag, default):
        child = elem.find(tag)
        if child is None or child.text is None or not child.text.strip():
            return default
        try:
            vals = [float(v) for v in child.text.split()]
        except ValueError:
            vals = []
        if len(vals) == 3:
            vals.append(1.0)
        if len(vals) != 4:
            raise self.err(child, '<%s> must be "r g b a", got %r' % (tag, child.text.strip()))
        return tuple(vals)

    def pose(self, elem, parent_frame=None):
        """The <pose> child of `elem` (identity when missing)."""
        child = elem.find('pose')
        if child is None:
            return Pose()
        rel = (child.get('relative_to') or child.get('frame') or '').strip()
        if rel and rel != parent_frame and rel != '__model__':
            raise self.err(child, '<pose relative_to/frame=%r> in <%s name=%r>: only poses '
                                  'relative to the parent frame%s are supported'
                           % (rel, elem.tag, elem.get('name', ''),
                              ' (%r)' % parent_frame if parent_frame else ''))
        try:
            return Pose.parse(child.text)
        except ValueError:
            raise self.err(child, '<pose> must be 6 numbers "x y z roll pitch yaw", got %r'
                           % (child.text or '').strip())

    def name(self, elem, what=None):
        n = (elem.get('name') or '').strip()
        if not n:
            raise self.err(elem, '<%s> needs a name attribute' % (what or elem.tag))
        return n


def sdf_version(doc):
    root = doc.root
    v = root.get('version', '1.6') if root.tag == 'sdf' else '1.6'
    try:
        parts = tuple(int(x) for x in v.strip().split('.')[:2])
    except ValueError:
        raise doc.error(root, '<sdf version=%r>: not a version number' % v)
    return parts
