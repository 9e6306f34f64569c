"""SDF of what the window inserts: Gazebo's simple shapes (unit box / sphere / cylinder as its
Insert toolbar makes them: 1 m, 1 kg, grey), its three light kinds, library models as
<include>s; and model names as Gazebo picks them (NAME, then NAME_0, NAME_1, ...). ROS-free."""
import math
from xml.sax.saxutils import escape

SHAPES = ('box', 'sphere', 'cylinder')
LIGHTS = ('point', 'spot', 'directional')

_GEOMETRY = {
    'box': '<box><size>1 1 1</size></box>',
    'sphere': '<sphere><radius>0.5</radius></sphere>',
    'cylinder': '<cylinder><radius>0.5</radius><length>1</length></cylinder>',
}
# inertia of 1 kg: box 1 m (1/6), sphere r 0.5 (2/5 m r^2), cylinder r 0.5 l 1
_INERTIA = {
    'box': (0.166667, 0.166667, 0.166667),
    'sphere': (0.1, 0.1, 0.1),
    'cylinder': (0.145833, 0.145833, 0.125),
}


def unique_name(base, taken):
    """`base` if free, else base_0, base_1, ... (Gazebo's naming of inserted models)."""
    taken = set(taken)
    if base not in taken:
        return base
    i = 0
    while '%s_%d' % (base, i) in taken:
        i += 1
    return '%s_%d' % (base, i)


def shape_sdf(kind, name):
    """Gazebo's unit_<kind> model (the shape's centre 0.5 m above the model origin is NOT
    used: the origin is the centre, the window places it 0.5 m above the ground)."""
    if kind not in SHAPES:
        raise ValueError('unknown shape %r (known: %s)' % (kind, ', '.join(SHAPES)))
    ixx, iyy, izz = _INERTIA[kind]
    g = _GEOMETRY[kind]
    return ('<sdf version="1.6"><model name="{n}"><link name="link">'
            '<inertial><mass>1</mass><inertia><ixx>{ixx}</ixx><ixy>0</ixy><ixz>0</ixz>'
            '<iyy>{iyy}</iyy><iyz>0</iyz><izz>{izz}</izz></inertia></inertial>'
            '<collision name="collision"><geometry>{g}</geometry></collision>'
            '<visual name="visual"><geometry>{g}</geometry><material>'
            '<script><name>Gazebo/Grey</name><uri>file://media/materials/scripts/gazebo.material'
            '</uri></script><ambient>0.3 0.3 0.3 1</ambient><diffuse>0.7 0.7 0.7 1</diffuse>'
            '</material></visual></link></model></sdf>').format(
                n=escape(name), ixx=ixx, iyy=iyy, izz=izz, g=g)


def light_sdf(kind, name):
    """Gazebo's user_<kind>_light as its Insert toolbar makes them."""
    if kind not in LIGHTS:
        raise ValueError('unknown light %r (known: %s)' % (kind, ', '.join(LIGHTS)))
    extra = ''
    if kind == 'spot':
        extra = ('<direction>0 0 -1</direction><spot><inner_angle>0.6</inner_angle>'
                 '<outer_angle>1</outer_angle><falloff>1</falloff></spot>')
    elif kind == 'directional':
        extra = '<direction>0.1 0.1 -0.9</direction>'
    return ('<sdf version="1.6"><light name="{n}" type="{k}"><diffuse>0.5 0.5 0.5 1</diffuse>'
            '<specular>0.1 0.1 0.1 1</specular><attenuation><range>20</range>'
            '<constant>0.5</constant><linear>0.01</linear><quadratic>0.001</quadratic>'
            '</attenuation><cast_shadows>{cs}</cast_shadows>{e}</light></sdf>').format(
                n=escape(name), k=kind, cs='true' if kind == 'directional' else 'false', e=extra)


def include_sdf(uri):
    """What Insert sends for a library model: <include> of its model:// URI (the simulator
    keeps it as an include in the saved world)."""
    return '<sdf version="1.6"><include><uri>%s</uri></include></sdf>' % escape(uri)


def wall_boxes(segments, height, thickness):
    """[(size (x, y, z), (cx, cy, cz), yaw)] of the walls ode_sim.description.walls.walls_model
    makes of `segments` [(x0, y0, x1, y1)]: a box of length (segment + thickness), standing on
    the ground, centred on the segment (the wall tool's preview while drawing)."""
    out = []
    for x0, y0, x1, y1 in segments:
        length = math.hypot(x1 - x0, y1 - y0)
        out.append(((length + thickness, thickness, height),
                    ((x0 + x1) / 2.0, (y0 + y1) / 2.0, height / 2.0),
                    math.atan2(y1 - y0, x1 - x0)))
    return out
