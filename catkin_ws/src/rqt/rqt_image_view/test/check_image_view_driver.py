#!/usr/bin/python3
"""Scripted `rqt_image_view <topic>`: waits for 5 frames, prints the frame's screen rectangle and
the mean colour of the last image, then waits for the test's screenshot (flag file argv[1])."""
import sys

from course_testing.rqt_driver import emit, file_exists, run, running_instance, widget_rect

flag = sys.argv.pop(1)
st = {}


def add_arguments(parser):
    group = parser.add_argument_group('Options for rqt_image_view plugin')
    group.add_argument('topic', nargs='?', help='The topic to subscribe to')


def scenario(main, step):
    v = running_instance(main, 'rqt_image_view/ImageView')
    if 'sent' not in st:
        if v.frames < 5:
            return False
        f = v.image_frame
        t = f._target()
        r = widget_rect(f)
        rgb = v._raw
        emit(kind='shown', frames=v.frames, topic=v.topics_combo_box.currentText(),
             image_rect=[r[0] + int(t.left()), r[1] + int(t.top()), int(t.width()), int(t.height())],
             size=[int(rgb.shape[1]), int(rgb.shape[0])], mean=[float(x) for x in rgb.reshape(-1, 3).mean(axis=0)],
             std=float(rgb.std()))
        st['sent'] = True
        return False
    return file_exists(flag)


sys.exit(run(['rqt_image_view'] + sys.argv[1:], scenario, standalone='rqt_image_view/ImageView',
             plugin_argument_provider=add_arguments))
