"""Where a spawned model lands: gazebo_ros_api_plugin's arithmetic (Noetic, Gazebo 11). ROS-free.

spawn_sdf_model / spawn_urdf_model put the model at `initial_pose` (in `reference_frame`)
composed with the model's OWN pose, as gazebo_ros' updateSDFAttributes / updateURDFModelPose
rewrite the XML before Gazebo loads it:

- the own pose is the `<pose>` of `<sdf><model>`, of the `<include>` of `<sdf><world><include>`
  (what `spawn_model -database` sends; Gazebo then uses it in place of the included file's own
  `<pose>`, so an include without `<pose>` has the identity), or of a URDF's `<robot><origin>`
  (sdformat's URDF parser takes it as the model pose; identity for an ordinary URDF);
- the result is `model_pose + Pose3d(initial_xyz, initial_q)` in ignition::math. Pose3d's
  `A + B` is "A expressed in frame B": position B.p + B.q * A.p * B.q^-1 (CoordPositionAdd),
  rotation B.q * A.q (CoordRotationAdd). In composition order that is B then A, i.e.
  `initial * own` with transforms.Pose's `*` (parent * child): the model's own pose is a pose
  relative to the requested initial pose.
- a reference frame (a link, model or the world) changes the initial pose first, as
  spawnSDFModel does: xyz = frame.q * xyz + frame.p, but q = initial_q * frame.q (ignition's
  `initial_q *= frame_pose.Rot()`: the frame's rotation applied in the initial pose's frame,
  not frame.q * initial_q). Both orders agree whenever the two rotations commute (e.g. both
  are yaws, the usual case).
"""
from ode_sim.description.transforms import Pose, quat_multiply


def initial_in_world(initial, frame=None):
    """The request's initial pose in the world, given the world pose of its reference frame
    (None: the world), with gazebo_ros' arithmetic (see the module's text)."""
    if frame is None:
        return initial.copy()
    return Pose(frame.p + frame.rotate(initial.p), quat_multiply(initial.q, frame.q))


def spawn_pose(initial, own=None, frame=None):
    """World pose of a spawned model: ignition's `own + initial` = initial * own, with the
    initial pose first taken into the world from `frame` (initial_in_world)."""
    start = initial_in_world(initial, frame)
    return start if own is None else start * own
