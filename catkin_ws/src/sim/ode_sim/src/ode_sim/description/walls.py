"""The window's wall tool (Gazebo's building editor, simplified): walls drawn as segments on the
ground become ONE static model, one link with a box collision and a box visual per wall, as the
building editor saves a building. ROS-free; the window spawns the text with
/gazebo/spawn_sdf_model (initial pose identity: the walls are placed in world coordinates), and
Save World writes it back as that model.

  walls_model(name, segments, height=2.5, thickness=0.15) -> SDF text
"""
import math
import xml.etree.ElementTree as ET

from ode_sim.description.model import ModelError
from ode_sim.description.save_world import num as _num

DEFAULT_HEIGHT = 2.5        # Gazebo's building editor's default wall height (m)
DEFAULT_THICKNESS = 0.15    # and thickness
MATERIAL = 'Gazebo/Grey'


def _finite(name, v):
    try:
        f = float(v)
    except (TypeError, ValueError):
        raise ModelError('walls: %s must be a number, got %r' % (name, v)) from None
    if not math.isfinite(f):
        raise ModelError('walls: %s must be finite, got %r' % (name, v))
    return f


def walls_model(name, segments, height=DEFAULT_HEIGHT, thickness=DEFAULT_THICKNESS):
    """SDF text of one static model `name` with a wall per segment (x0, y0, x1, y1) in the
    world's ground plane: a box of length (segment + thickness, so that walls meeting at a
    corner close it), thickness and height standing on the ground, centred on the segment.
    Bad input raises ModelError with one line naming what is wrong."""
    name = (name or '').strip() if isinstance(name, str) else ''
    if not name:
        raise ModelError('walls: the model needs a name')
    height = _finite('height', height)
    thickness = _finite('thickness', thickness)
    if height <= 0 or thickness <= 0:
        raise ModelError('walls: height and thickness must be positive, got %g and %g'
                         % (height, thickness))
    segments = list(segments or [])
    if not segments:
        raise ModelError('walls: no wall segments')
    sdf = ET.Element('sdf', version='1.6')
    model = ET.SubElement(sdf, 'model', name=name)
    ET.SubElement(model, 'static').text = 'true'
    ET.SubElement(model, 'pose').text = '0 0 0 0 0 0'
    link = ET.SubElement(model, 'link', name='link')
    for i, seg in enumerate(segments):
        try:
            x0, y0, x1, y1 = (_finite('segment %d' % i, v) for v in seg)
        except (TypeError, ValueError):
            raise ModelError('walls: segment %d must be (x0, y0, x1, y1), got %r' % (i, seg)) \
                from None
        length = math.hypot(x1 - x0, y1 - y0)
        if length < 1e-6:
            raise ModelError('walls: segment %d has zero length (%g, %g)' % (i, x0, y0))
        pose = '%s %s %s 0 0 %s' % (_num((x0 + x1) / 2), _num((y0 + y1) / 2), _num(height / 2),
                                    _num(math.atan2(y1 - y0, x1 - x0)))
        size = '%s %s %s' % (_num(length + thickness), _num(thickness), _num(height))
        for kind in ('collision', 'visual'):
            el = ET.SubElement(link, kind, name='wall_%d_%s' % (i, kind))
            ET.SubElement(el, 'pose').text = pose
            box = ET.SubElement(ET.SubElement(el, 'geometry'), 'box')
            ET.SubElement(box, 'size').text = size
            if kind == 'visual':
                mat = ET.SubElement(el, 'material')
                script = ET.SubElement(mat, 'script')
                ET.SubElement(script, 'uri').text = 'file://media/materials/scripts/gazebo.material'
                ET.SubElement(script, 'name').text = MATERIAL
    ET.indent(sdf, '  ')
    return '<?xml version="1.0" ?>\n' + ET.tostring(sdf, encoding='unicode') + '\n'
