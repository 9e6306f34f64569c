"""The simulator's description of a world: what the SDF and URDF loaders produce and what the
physics, the ray caster, the renderer and the plugins consume. Plain data, no ODE here.

Frames (the SDF convention, also used for robots loaded from URDF):
- `Model.pose`: the model frame in the world.
- `Link.pose`: the link frame in the model frame (URDF: forward kinematics at zero joint
  positions, after fixed joints are lumped into their parent the way Gazebo does).
- `Collision.pose`, `Visual.pose`, `Sensor.pose`, `Inertial.pose`: relative to their link.
- `Joint.anchor`, `Joint.axis`: in the model frame (unit axis); `parent` is a link name or
  'world'.
"""
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Tuple

import numpy as np

from ode_sim.description.transforms import Pose


class ModelError(Exception):
    """Bad input: the message is the one line shown to the user, naming file/element and
    what is wrong."""


@dataclass
class Geometry:
    kind: str                       # 'box' | 'cylinder' | 'sphere' | 'plane' | 'mesh'
    size: Tuple[float, float, float] = (0.0, 0.0, 0.0)   # box: full extents x y z
    radius: float = 0.0             # cylinder, sphere
    length: float = 0.0             # cylinder (along local Z)
    normal: Tuple[float, float, float] = (0.0, 0.0, 1.0)  # plane
    plane_size: Tuple[float, float] = (100.0, 100.0)     # plane: extent for drawing only
    uri: str = ''                   # mesh: the URI as written
    filename: str = ''              # mesh: resolved absolute path
    scale: Tuple[float, float, float] = (1.0, 1.0, 1.0)  # mesh
    vertices: Optional[np.ndarray] = None   # mesh: (N, 3) float, already scaled
    faces: Optional[np.ndarray] = None      # mesh: (M, 3) int
    submesh: str = ''               # mesh: <submesh><name>, '' the whole file
    center: bool = False            # mesh: <submesh><center>
    parts: list = field(default_factory=list)   # mesh: render parts (description.mesh.MeshPart)


@dataclass
class Material:
    """A visual's look: a mesh file's material (COLLADA effect, MTL), an OGRE material script
    or SDF <ambient>/<diffuse>/<specular>/<emissive>."""
    name: str = ''
    diffuse: Tuple[float, float, float, float] = (0.7, 0.7, 0.7, 1.0)
    ambient: Optional[Tuple[float, float, float, float]] = None   # None: the diffuse colour
    emissive: Tuple[float, float, float] = (0.0, 0.0, 0.0)
    specular: Tuple[float, float, float] = (0.0, 0.0, 0.0)
    opacity: float = 1.0
    texture: str = ''               # absolute path of the diffuse texture image, '' none
    uv_scale: Tuple[float, float] = (1.0, 1.0)   # OGRE texture_unit scale (uv / scale)
    source: str = ''                # where it was defined, for messages


@dataclass
class Surface:
    """Contact parameters (SDF <surface>, URDF <gazebo reference> mu1 mu2 kp kd ...)."""
    mu1: float = 1.0
    mu2: float = 1.0
    fdir1: Optional[Tuple[float, float, float]] = None
    kp: float = 1e12
    kd: float = 1.0
    max_vel: float = 0.01
    min_depth: float = 0.0
    bounce: float = 0.0
    bounce_threshold: float = 100000.0
    slip1: float = 0.0
    slip2: float = 0.0


@dataclass
class Collision:
    name: str
    geometry: Geometry
    pose: Pose = field(default_factory=Pose)
    surface: Surface = field(default_factory=Surface)
    laser_retro: float = 0.0


@dataclass
class Visual:
    name: str
    geometry: Geometry
    pose: Pose = field(default_factory=Pose)
    color: Tuple[float, float, float, float] = (0.7, 0.7, 0.7, 1.0)   # diffuse RGBA
    material_name: str = ''         # e.g. 'Gazebo/Red' when given by name
    material: Optional[Material] = None   # the visual's own material (overrides the mesh's)


@dataclass
class Inertial:
    mass: float
    pose: Pose = field(default_factory=Pose)   # centre of mass frame, relative to the link
    ixx: float = 0.0
    ixy: float = 0.0
    ixz: float = 0.0
    iyy: float = 0.0
    iyz: float = 0.0
    izz: float = 0.0

    def tensor(self):
        return np.array([[self.ixx, self.ixy, self.ixz],
                         [self.ixy, self.iyy, self.iyz],
                         [self.ixz, self.iyz, self.izz]])


@dataclass
class Plugin:
    name: str
    filename: str                   # e.g. 'libgazebo_ros_diff_drive.so'
    params: Dict[str, str] = field(default_factory=dict)   # child tag -> stripped text
    element: object = None          # the xml.etree Element, for nested parameters
    source: str = ''                # 'FILE' or 'FILE:<gazebo>' for messages


@dataclass
class Sensor:
    name: str
    type: str                       # 'ray' | 'gpu_ray' | 'camera' | 'depth' | 'imu' | 'contact'
    link: str                       # link it is attached to (after lumping)
    pose: Pose = field(default_factory=Pose)   # relative to that link
    update_rate: float = 0.0        # Hz, 0 = every step
    always_on: bool = True
    visualize: bool = False
    topic: str = ''
    # ray: samples resolution min_angle max_angle (horizontal), v_samples v_min_angle
    #      v_max_angle, range_min range_max range_resolution, noise_mean noise_stddev
    # camera/depth: horizontal_fov width height format near far noise_mean noise_stddev
    # imu: angular_velocity/linear_acceleration noise (noise_stddev)
    # contact: collisions (names of the link's collisions it reports)
    params: Dict[str, object] = field(default_factory=dict)
    plugins: List[Plugin] = field(default_factory=list)
    element: object = None          # the SDF <sensor> element (Save World writes it back)


@dataclass
class Link:
    name: str
    pose: Pose = field(default_factory=Pose)
    inertial: Optional[Inertial] = None
    collisions: List[Collision] = field(default_factory=list)
    visuals: List[Visual] = field(default_factory=list)
    sensors: List[Sensor] = field(default_factory=list)
    gravity: bool = True
    self_collide: bool = False
    kinematic: bool = False
    # links lumped into this one (URDF fixed joints): name -> pose relative to this link
    lumped: Dict[str, Pose] = field(default_factory=dict)


@dataclass
class Joint:
    name: str
    type: str                       # 'revolute' | 'continuous' | 'prismatic' | 'fixed' | 'ball'
    parent: str                     # link name or 'world'
    child: str
    anchor: np.ndarray = field(default_factory=lambda: np.zeros(3))      # model frame
    axis: np.ndarray = field(default_factory=lambda: np.array([1.0, 0.0, 0.0]))  # model frame
    lower: Optional[float] = None   # None: no limit
    upper: Optional[float] = None
    effort: Optional[float] = None  # max |effort|, None = unlimited
    velocity: Optional[float] = None
    damping: float = 0.0
    friction: float = 0.0
    origin: Pose = field(default_factory=Pose)   # URDF: joint frame in the parent link frame


@dataclass
class Transmission:
    name: str
    type: str
    joints: Dict[str, List[str]] = field(default_factory=dict)  # joint -> hardware interfaces
    actuators: Dict[str, float] = field(default_factory=dict)   # actuator -> reduction


@dataclass
class Model:
    name: str
    pose: Pose = field(default_factory=Pose)
    static: bool = False
    links: List[Link] = field(default_factory=list)
    joints: List[Joint] = field(default_factory=list)
    plugins: List[Plugin] = field(default_factory=list)
    transmissions: List[Transmission] = field(default_factory=list)
    robot_namespace: str = ''
    source: str = ''                # file the model came from, for messages
    urdf: str = ''                  # the URDF text when spawned from URDF
    canonical_link: str = ''        # root link (model pose reports this link's pose)
    allow_auto_disable: bool = True  # SDF <allow_auto_disable>: may sleep when at rest
    # where it came from, for Save World (description/save_world.py): a world <include> or a
    # spawned <include> of model://NAME keeps its URI; an SDF <model> its element
    include_uri: str = ''
    sdf_element: object = None
    warnings: List[str] = field(default_factory=list)

    def link(self, name):
        for link in self.links:
            if link.name == name:
                return link
        return None

    def joint(self, name):
        for joint in self.joints:
            if joint.name == name:
                return joint
        return None


@dataclass
class Physics:
    max_step_size: float = 0.001
    real_time_update_rate: float = 1000.0
    real_time_factor: float = 1.0
    max_contacts: int = 20
    solver_type: str = 'quick'
    iters: int = 50
    sor: float = 1.3
    cfm: float = 0.0
    erp: float = 0.2
    contact_max_correcting_vel: float = 100.0
    contact_surface_layer: float = 0.001


@dataclass
class Light:
    name: str
    type: str = 'directional'       # 'directional' | 'point' | 'spot'
    pose: Pose = field(default_factory=Pose)
    diffuse: Tuple[float, float, float, float] = (0.8, 0.8, 0.8, 1.0)
    specular: Tuple[float, float, float, float] = (0.2, 0.2, 0.2, 1.0)
    direction: Tuple[float, float, float] = (-0.5, 0.1, -0.9)
    cast_shadows: bool = True
    attenuation_range: float = 1000.0


@dataclass
class Scene:
    ambient: Tuple[float, float, float, float] = (0.4, 0.4, 0.4, 1.0)
    background: Tuple[float, float, float, float] = (0.7, 0.7, 0.7, 1.0)
    shadows: bool = True


@dataclass
class World:
    name: str = 'default'
    gravity: Tuple[float, float, float] = (0.0, 0.0, -9.8)
    physics: Physics = field(default_factory=Physics)
    scene: Scene = field(default_factory=Scene)
    lights: List[Light] = field(default_factory=list)
    models: List[Model] = field(default_factory=list)
    plugins: List[Plugin] = field(default_factory=list)
    source: str = ''
    warnings: List[str] = field(default_factory=list)
