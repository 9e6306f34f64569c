"""libgazebo_ros_multicamera.so (gazebo_plugins noetic-devel): the stereo camera plugin of a
<sensor type="multicamera">. Each <camera> whose name contains "left" or "right" becomes a
libgazebo_ros_camera.so camera (camera.py: same tags, images and camera_info) named
`<cameraName>/left` or `<cameraName>/right`, so the topics are
`<robotNamespace>/<cameraName>/left/image_raw`, `.../right/camera_info`, ... The left
camera's CameraInfo has no baseline; the right one's P[0][3] = -f * hackBaseline, as the
original (which passes hackBaseline to the right camera only). Each camera looks from the
sensor pose composed with its own <pose>, with its own <image>, <horizontal_fov> and <clip>;
both share frameName (the original's single frame). Other cameras are skipped with a warning
(the original makes no ROS side for them either).
"""
import copy

import rospy

from ode_sim.ros.plugins.base import Plugin
from ode_sim.ros.plugins.camera import CameraPlugin


class MultiCameraPlugin(Plugin):
    """libgazebo_ros_multicamera.so"""

    sensor_plugin = True

    def __init__(self, ctx, model, desc, sensor=None):
        super().__init__(ctx, model, desc, sensor)
        if sensor is None or sensor.type != 'multicamera':
            raise self.error('must be inside a <sensor type="multicamera">')
        base_name = self.params.get('cameraName', '').strip()
        baseline = self.param('hackBaseline', 0.0, float, warn=False)
        self.cameras = []
        for cam in sensor.params.get('cameras', []):
            if 'left' in cam['name']:
                suffix, hack = 'left', 0.0
            elif 'right' in cam['name']:
                suffix, hack = 'right', baseline
            else:
                rospy.logwarn('%s: camera %r of sensor %r is neither left nor right: no ROS '
                              'topics for it' % (self.label, cam['name'], sensor.name))
                continue
            view = copy.copy(sensor)
            view.params = dict(sensor.params)
            view.params.update({k: v for k, v in cam.items() if k not in ('name', 'pose')})
            view.pose = sensor.pose * cam['pose']
            view.name = '%s_%s' % (sensor.name, suffix)
            d = copy.copy(desc)
            d.params = dict(desc.params)
            d.params['cameraName'] = (base_name + '/' + suffix) if base_name else suffix
            d.params['hackBaseline'] = repr(hack)
            self.cameras.append(CameraPlugin(ctx, model, d, view))

    def update(self):
        for c in self.cameras:
            c.update()

    def wait(self, timeout=None):
        for c in self.cameras:
            c.wait(timeout)

    def reset(self):
        super().reset()
        for c in self.cameras:
            c.reset()

    def shutdown(self):
        for c in self.cameras:
            c.shutdown()


PLUGINS = {'libgazebo_ros_multicamera.so': MultiCameraPlugin}
