"""libgazebo_ros_triggered_camera.so (gazebo_plugins noetic-devel): the camera of
libgazebo_ros_camera.so (same tags, topics and images, see camera.py) that renders only when
triggered: every std_msgs/Empty on `<robotNamespace>/<cameraName>/<triggerTopicName>` (default
`image_trigger`; an absolute name stays as written) asks for one frame, and the camera publishes
exactly one image (and camera_info) per trigger, stamped with the sim time it was taken at.
Triggers that arrive while a frame is being rendered are kept and served one after another.
Nothing is rendered while nobody subscribes to the image; a trigger then waits.
"""
import threading

from std_msgs.msg import Empty

from ode_sim.ros.plugins.camera import CameraPlugin
from ode_sim.ros.plugins.rosio import close


class TriggeredCameraPlugin(CameraPlugin):
    """libgazebo_ros_triggered_camera.so"""

    def __init__(self, ctx, model, desc, sensor=None):
        super().__init__(ctx, model, desc, sensor)
        name = self.param('triggerTopicName', 'image_trigger', warn=False).strip()
        base = (self.topic(self.camera_name) if self.camera_name else self.topic('')).rstrip('/')
        self.trigger_topic = name if name.startswith('/') else base + '/' + name
        self._trigger_lock = threading.Lock()
        self.triggered = 0
        self.trigger_sub = ctx.io.subscriber(self.trigger_topic, Empty, self.on_trigger,
                                             queue_size=10)

    def on_trigger(self, _msg=None):
        with self._trigger_lock:
            self.triggered += 1

    def next_update(self):
        return None if self.triggered > 0 else float('inf')

    def due(self):
        return True         # a trigger asks for the next frame, whatever the sensor's rate

    def update(self):
        if self.triggered <= 0:
            return
        before_future, before_frames = self._future, self.frames
        super().update()
        started = (self._future is not None and self._future is not before_future) \
            or self.frames != before_frames
        if started:
            with self._trigger_lock:
                self.triggered -= 1

    def shutdown(self):
        close(self.trigger_sub)
        super().shutdown()


PLUGINS = {'libgazebo_ros_triggered_camera.so': TriggeredCameraPlugin}
