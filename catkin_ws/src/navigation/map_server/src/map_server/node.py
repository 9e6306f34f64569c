"""ROS wiring of the map_server and map_saver executables (argument parsing, topics, services).
The map logic is in map_io / saver, the message conversion in conversions."""
import sys
import threading
import time

from map_server.map_io import MapConfig, MapError, load_image_grid, parse_map_yaml, TRINARY
from map_server.saver import DEFAULT_FREE, DEFAULT_OCC, SaverError, check_thresholds, save_map

MAP_SERVER_USAGE = ('\nUSAGE: map_server <map.yaml>\n'
                    '  map.yaml: map description file\n'
                    'DEPRECATED USAGE: map_server <map> <resolution>\n'
                    '  map: image file to load\n'
                    '  resolution: map resolution [meters/pixel]')
MAP_SAVER_USAGE = ('Usage: \n'
                   '  map_saver -h\n'
                   '  map_saver [--occ <threshold_occupied>] [--free <threshold_free>] [-f <mapname>] '
                   '[ROS remapping args]')


def _error(msg):
    """ROS_ERROR's console format, usable before the node exists (no master needed)."""
    sys.stderr.write('[ERROR] [%.6f]: %s\n' % (time.time(), msg))
    sys.stderr.flush()


def _load(argv):
    """argv without remaps -> (Grid, description) or raises MapError/ValueError for usage."""
    if len(argv) == 2:
        cfg = parse_map_yaml(argv[1])
        return cfg, False
    if len(argv) == 3:
        try:
            res = float(argv[2])
        except ValueError:
            raise MapError('The map resolution "%s" is not a number.' % argv[2])
        if res <= 0.0:
            raise MapError('The map resolution must be > 0 (got %s).' % argv[2])
        return MapConfig(argv[1], res, (0.0, 0.0, 0.0), False, 0.65, 0.196, TRINARY), True
    raise ValueError(MAP_SERVER_USAGE)


def map_server_main():
    import rospy
    from nav_msgs.msg import MapMetaData
    from nav_msgs.srv import LoadMap, LoadMapResponse
    from map_server.conversions import NumpyGetMap, NumpyGetMapResponse, NumpyOccupancyGrid, \
        grid_to_msg

    argv = rospy.myargv(sys.argv)
    try:
        cfg, deprecated = _load(argv)
        grid = load_image_grid(cfg)
    except ValueError as e:
        _error(str(e))
        return 255
    except MapError as e:
        _error(str(e))
        return 255

    rospy.init_node('map_server', anonymous=True)
    if deprecated:
        rospy.logwarn('Using deprecated map server interface. Please switch to new interface.')
        cfg.negate = bool(rospy.get_param('~negate', 0))
        cfg.occupied_thresh = float(rospy.get_param('~occupied_thresh', 0.65))
        cfg.free_thresh = float(rospy.get_param('~free_thresh', 0.196))
        grid = load_image_grid(cfg)
    frame_id = rospy.get_param('~frame_id', 'map')
    rospy.loginfo('Loading map from image "%s"', cfg.image)
    rospy.loginfo('Read a %d X %d map @ %.3f m/cell', grid.width, grid.height, grid.resolution)

    # sim time: wait for a valid clock before stamping the map (ros::Time::waitForValid)
    while not rospy.is_shutdown() and rospy.Time.now().is_zero():
        time.sleep(0.01)
    if rospy.is_shutdown():
        return 0
    state = {'msg': grid_to_msg(grid, frame_id, rospy.Time.now())}
    lock = threading.Lock()
    meta_pub = rospy.Publisher('map_metadata', MapMetaData, queue_size=1, latch=True)
    map_pub = rospy.Publisher('map', NumpyOccupancyGrid, queue_size=1, latch=True)

    def publish():
        with lock:
            msg = state['msg']
        meta_pub.publish(msg.info)
        map_pub.publish(msg)

    def on_static_map(_req):
        rospy.loginfo('Sending map')
        with lock:
            return NumpyGetMapResponse(map=state['msg'])

    def on_change_map(req):
        resp = LoadMapResponse()
        try:
            new_grid = load_image_grid(parse_map_yaml(req.map_url))
        except MapError as e:
            rospy.logerr('%s', e)
            resp.result = LoadMapResponse.RESULT_UNDEFINED_FAILURE
            return resp
        with lock:
            state['msg'] = grid_to_msg(new_grid, frame_id, rospy.Time.now())
        publish()
        rospy.loginfo('Changed map to %s', req.map_url)
        resp.result = LoadMapResponse.RESULT_SUCCESS
        return resp

    rospy.Service('static_map', NumpyGetMap, on_static_map)
    rospy.Service('change_map', LoadMap, on_change_map)
    publish()
    rospy.spin()
    return 0


def parse_saver_args(args):
    """map_saver's arguments (remaps already removed) -> (mapname, occ, free) or raises SaverError;
    returns None for -h."""
    mapname, occ, free = 'map', DEFAULT_OCC, DEFAULT_FREE
    i = 0
    while i < len(args):
        a = args[i]
        if a == '-h':
            return None
        if a in ('-f', '--occ', '--free'):
            if i + 1 >= len(args):
                raise SaverError(MAP_SAVER_USAGE)
            value = args[i + 1]
            if a == '-f':
                mapname = value
            else:
                try:
                    number = int(value)
                except ValueError:
                    raise SaverError('%s needs an integer, got "%s"\n%s' % (a, value, MAP_SAVER_USAGE))
                if a == '--occ':
                    occ = number
                else:
                    free = number
            i += 2
        else:
            raise SaverError(MAP_SAVER_USAGE)
    check_thresholds(occ, free)
    return mapname, occ, free


def map_saver_main():
    import rospy
    from map_server.conversions import NumpyOccupancyGrid, msg_to_grid

    try:
        parsed = parse_saver_args(rospy.myargv(sys.argv)[1:])
    except SaverError as e:
        text = str(e)
        if text == MAP_SAVER_USAGE:
            print(text)
        else:
            _error(text)
        return 1
    if parsed is None:
        print(MAP_SAVER_USAGE)
        return 0
    mapname, occ, free = parsed
    rospy.init_node('map_saver')
    done = threading.Event()
    failed = []

    def on_map(msg):
        if done.is_set():
            return
        grid = msg_to_grid(msg)
        rospy.loginfo('Received a %d X %d map @ %.3f m/pix', grid.width, grid.height, grid.resolution)
        try:
            save_map(grid, mapname, occ, free, log=lambda s: rospy.loginfo('%s', s))
            rospy.loginfo('Done\n')
        except OSError as e:
            rospy.logerr("Couldn't save map file to %s: %s", mapname, e)
            failed.append(e)
        done.set()

    rospy.loginfo('Waiting for the map')
    rospy.Subscriber('map', NumpyOccupancyGrid, on_map, queue_size=1, buff_size=2 ** 26)
    while not done.is_set() and not rospy.is_shutdown():
        done.wait(0.1)
    return 1 if failed or not done.is_set() else 0
