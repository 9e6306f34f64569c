"""The engine: physics (PhysicsWorld, the only owner of ODE objects), ray casting, rendering
and the sensors' maths. No ROS imports."""
# the compiled core (_core, built by catkin) lands in the devel/install space's ode_sim/engine
from pkgutil import extend_path
__path__ = extend_path(__path__, __name__)
