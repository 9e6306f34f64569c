"""Lab 4: a robot of the practical works in a scene of its own, through ros_control.

criteria.py  the lab's package, launch file, grader and criteria texts
variants.py  the variant's lidar, camera and body (labs/lab4/variants.yaml)
scene.py     the scene (SDF world): light, ground, gravity, objects
robot.py     the robot description and its controllers: drive plugins, wheels, by velocity
motion.py    the robot's track and the scene objects' poses on sim time
rules.py     pure logic: an observation -> the nine criteria (no rospy)
observer.py  the rospy side: roslaunch lab4.launch headless, watch sensors, controllers, motion

Time base: every duration of the run is the student's own simulation time (/clock); wall-clock
limits only bound how long the grader waits (generous, for slow machines) and say so.

Definitions (also in labs/lab4/README.md):
  scene object    an <include> of a model:// model other than sun / ground_plane, or an inline
                  <model> with a <mesh> geometry; objects are different when their URIs
                  (include) or mesh URIs (inline) differ;
  light           a <light> or an include of model://sun;  ground: model://ground_plane or a
                  model with a <plane> geometry;  gravity: a <gravity> element, z < 0;
  wheel           a continuous joint whose child link has a cylinder collision;
  by velocity     a running controller that commands the wheel's velocity claims it: by type
                  velocity_controllers/JointVelocityController or JointGroupVelocityController,
                  effort_controllers/JointVelocityController (the book's §12.4: a velocity PID
                  on the EffortJointInterface), diff_drive_controller and the other drive
                  controllers of ros_controllers; a position, trajectory or effort controller
                  does not, whatever its interface; a type unknown here counts when it claims
                  the wheel under VelocityJointInterface;
  collision       a scene object displaced by more than 3 cm (or turned by more than 0.1 rad)
                  during the run, or the robot tipped (roll or pitch above 0.35 rad).
"""
from grading.lab4.criteria import CRITERIA, DEFAULT_TIMEOUT, GRADER_PKG, LAUNCH, PACKAGE

__all__ = ['CRITERIA', 'DEFAULT_TIMEOUT', 'GRADER_PKG', 'LAUNCH', 'PACKAGE']
