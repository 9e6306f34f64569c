"""The engine: physics (PhysicsWorld, the only owner of ODE objects), ray casting, rendering
and the sensors' maths. No ROS imports."""
