"""Loading the C++ hot loops that navigation packages build with catkin (libNAME.so in the
workspace's devel/lib or an install's lib), through ctypes: one finder for all of them."""
import ctypes
import os


def find_library(lib_name, package):
    """Path of lib_name in the lib directories of CMAKE_PREFIX_PATH (also lib/<package>) and
    LD_LIBRARY_PATH; ImportError naming what to do when it is not built."""
    dirs = []
    for prefix in os.environ.get('CMAKE_PREFIX_PATH', '').split(':'):
        if prefix:
            dirs += [os.path.join(prefix, 'lib'), os.path.join(prefix, 'lib', package)]
    dirs += os.environ.get('LD_LIBRARY_PATH', '').split(':')
    for d in dirs:
        p = os.path.join(d, lib_name)
        if d and os.path.exists(p):
            return p
    raise ImportError('%s not found in the CMAKE_PREFIX_PATH / LD_LIBRARY_PATH lib '
                      'directories: build the workspace and source devel/setup.bash' % lib_name)


def load_library(lib_name, package, functions):
    """ctypes.CDLL of lib_name with each function's (restype, argtypes) of `functions` set."""
    lib = ctypes.CDLL(find_library(lib_name, package))
    for name, (restype, argtypes) in functions.items():
        fn = getattr(lib, name)
        fn.restype = restype
        fn.argtypes = argtypes
    return lib
