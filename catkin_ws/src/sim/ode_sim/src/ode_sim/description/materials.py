"""Colours of Gazebo's named materials (`<material><script><name>Gazebo/Red</name>` in SDF,
`<gazebo reference="L"><material>Gazebo/Red</material>` in URDF).

Values are the `diffuse` colours of gazebo-classic's media/materials/scripts/gazebo.material
(alpha 0.5 / 0.4 where the material blends with that alpha). Materials that are a texture in
Gazebo (Wood, WoodFloor, Bricks, ...) have no single colour there; for them the table holds an
approximate mean colour of the texture, marked 'texture' below. Gazebo/Indigo and
Gazebo/DarkYellow were added to gazebo.material in Gazebo 9/11; their values are quoted from
that version.
"""

GREY = (0.7, 0.7, 0.7, 1.0)

GAZEBO_MATERIALS = {
    'Gazebo/Grey': (0.7, 0.7, 0.7, 1.0),
    'Gazebo/Gray': (0.7, 0.7, 0.7, 1.0),          # common misspelling; not in gazebo.material
    'Gazebo/DarkGrey': (0.175, 0.175, 0.175, 1.0),
    'Gazebo/LightGrey': (0.8, 0.8, 0.8, 1.0),      # not in gazebo.material; a light grey
    'Gazebo/White': (1.0, 1.0, 1.0, 1.0),
    'Gazebo/FlatBlack': (0.1, 0.1, 0.1, 1.0),
    'Gazebo/Black': (0.0, 0.0, 0.0, 1.0),
    'Gazebo/Red': (1.0, 0.0, 0.0, 1.0),
    'Gazebo/RedBright': (0.87, 0.26, 0.07, 1.0),
    'Gazebo/Green': (0.0, 1.0, 0.0, 1.0),
    'Gazebo/Blue': (0.0, 0.0, 1.0, 1.0),
    'Gazebo/SkyBlue': (0.0, 0.0, 1.0, 1.0),        # diffuse 0 0 1 (ambient 0.13 0.44 0.70)
    'Gazebo/Yellow': (1.0, 1.0, 0.0, 1.0),
    'Gazebo/ZincYellow': (0.9725, 0.9529, 0.2078, 1.0),
    'Gazebo/DarkYellow': (0.7, 0.7, 0.0, 1.0),
    'Gazebo/Purple': (1.0, 0.0, 1.0, 1.0),
    'Gazebo/Turquoise': (0.0, 1.0, 1.0, 1.0),
    'Gazebo/Orange': (1.0, 0.5088, 0.0468, 1.0),
    'Gazebo/Indigo': (0.33, 0.0, 0.5, 1.0),
    'Gazebo/Gold': (0.8, 0.64869, 0.120759, 1.0),
    'Gazebo/Pioneer2Body': (0.681193, 0.000923, 0.000923, 1.0),
    'Gazebo/WhiteGlow': (1.0, 1.0, 1.0, 1.0),
    'Gazebo/RedGlow': (1.0, 0.0, 0.0, 1.0),
    'Gazebo/GreenGlow': (0.0, 1.0, 0.0, 1.0),
    'Gazebo/BlueGlow': (0.0, 0.0, 1.0, 1.0),
    'Gazebo/YellowGlow': (1.0, 1.0, 0.0, 1.0),
    'Gazebo/PurpleGlow': (1.0, 0.0, 1.0, 1.0),
    'Gazebo/TurquoiseGlow': (0.0, 1.0, 1.0, 1.0),
    'Gazebo/TurquoiseGlowOutline': (0.0, 1.0, 1.0, 1.0),
    'Gazebo/RedTransparent': (1.0, 0.0, 0.0, 0.5),
    'Gazebo/GreenTransparent': (0.0, 1.0, 0.0, 0.5),
    'Gazebo/BlueTransparent': (0.0, 0.0, 1.0, 0.5),
    'Gazebo/GreyTransparent': (0.5, 0.5, 0.5, 0.5),
    'Gazebo/YellowTransparent': (1.0, 1.0, 0.0, 0.5),
    'Gazebo/OrangeTransparent': (1.0, 0.44, 0.0, 0.4),
    'Gazebo/RedTransparentOverlay': (1.0, 0.0, 0.0, 0.5),
    'Gazebo/GreenTransparentOverlay': (0.0, 1.0, 0.0, 0.5),
    'Gazebo/BlueTransparentOverlay': (0.0, 0.0, 1.0, 0.5),
    'Gazebo/BlueLaser': (0.0, 0.0, 1.0, 0.4),
    'Gazebo/LightOn': (0.0, 1.0, 0.0, 1.0),
    'Gazebo/LightOff': (1.0, 0.0, 0.0, 1.0),
    'Gazebo/JointAnchor': (1.0, 1.0, 1.0, 1.0),
    'Gazebo/Road': (0.8, 0.8, 0.8, 1.0),
    'Gazebo/Residential': (0.8, 0.8, 0.8, 1.0),
    'Gazebo/Tertiary': (0.8, 0.8, 0.8, 1.0),
    'Gazebo/Pedestrian': (0.8, 0.8, 0.8, 1.0),
    'Gazebo/Footway': (0.8, 0.8, 0.8, 1.0),
    'Gazebo/Motorway': (0.8, 0.8, 0.8, 1.0),
    'Gazebo/Primary': (0.8, 0.8, 0.8, 1.0),
    'Gazebo/Secondary': (0.8, 0.8, 0.8, 1.0),
    'Gazebo/Steps': (0.8, 0.8, 0.8, 1.0),
    # texture materials: approximate mean colour of the texture
    'Gazebo/Wood': (0.62, 0.42, 0.22, 1.0),            # texture wood.jpg
    'Gazebo/WoodFloor': (0.55, 0.38, 0.22, 1.0),       # texture hardwood_floor.jpg
    'Gazebo/WoodPallet': (0.66, 0.52, 0.36, 1.0),      # texture WoodPallet.png
    'Gazebo/Bricks': (0.62, 0.33, 0.26, 1.0),          # texture bricks.png
    'Gazebo/CeilingTiled': (0.85, 0.85, 0.82, 1.0),    # texture ceiling_tiled.jpg
    'Gazebo/PaintedWall': (0.9, 0.88, 0.82, 1.0),      # texture paintedWall.jpg
    'Gazebo/PioneerBody': (0.7, 0.05, 0.05, 1.0),      # texture pioneerBody.jpg, diffuse red
    'Gazebo/WindowFrame': (0.75, 0.75, 0.75, 1.0),     # texture window_frame.png
    'Gazebo/Grass': (0.25, 0.5, 0.15, 1.0),            # texture grass (model materials)
    'Gazebo/GreyGradientSky': (0.7, 0.7, 0.7, 1.0),
    'Gazebo/CloudySky': (0.7, 0.75, 0.85, 1.0),
}

_LOWER = {k.lower(): v for k, v in GAZEBO_MATERIALS.items()}


def material_color(name, warnings=None, where=''):
    """Diffuse RGBA of Gazebo material `name`. Unknown: a warning (appended to `warnings` when
    given, naming `where`) and grey."""
    key = (name or '').strip()
    color = GAZEBO_MATERIALS.get(key) or _LOWER.get(key.lower())
    if color is not None:
        return color
    if warnings is not None:
        warnings.append('%sunknown material %r, drawn grey (known: Gazebo/Red, Gazebo/Grey, ...)'
                        % (where + ': ' if where else '', key))
    return GREY


def is_known(name):
    key = (name or '').strip()
    return key in GAZEBO_MATERIALS or key.lower() in _LOWER
