"""Shape instances: one collision or visual of one link, with a way to get its current pose in
the world. The physics world hands lists of these to the ray caster (collisions) and to the
renderer (visuals); static shapes keep a fixed pose."""
from dataclasses import dataclass, field
from typing import Callable, Optional, Tuple

from ode_sim.description.model import Geometry
from ode_sim.description.transforms import Pose


@dataclass(eq=False)
class ShapeInstance:
    key: str                                   # 'model::link::name', unique in a world
    model: str
    link: str
    geometry: Geometry
    local: Pose = field(default_factory=Pose)  # shape frame relative to the link frame
    color: Tuple[float, float, float, float] = (0.7, 0.7, 0.7, 1.0)
    link_pose: Optional[Callable[[], Pose]] = None   # current link pose in the world; None = static
    static_pose: Pose = field(default_factory=Pose)  # link pose in the world when static
    laser_retro: float = 0.0                   # collisions: <laser_retro>, the lidar intensity
    material: Optional[object] = None          # visuals: model.Material of the visual, or None

    @property
    def static(self):
        return self.link_pose is None

    def world_pose(self):
        """Current pose of the shape frame in the world."""
        base = self.static_pose if self.link_pose is None else self.link_pose()
        return base * self.local
