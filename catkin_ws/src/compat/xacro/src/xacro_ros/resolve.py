"""ROS 1 semantics for xacro's `$(find pkg)`, installed into the PyPI xacro 2.1.1 module.

PyPI xacro resolves `$(find pkg)` through ament_index_python (ROS 2 share directories); in
ROS 1, xacro resolves it as roslaunch does: `rospkg.RosPack().get_path(pkg)`, i.e. the package
directory found on ROS_PACKAGE_PATH (a catkin source folder or an installed share folder).
"""
import os
import sys

_REPO_DEPS = os.path.join(os.path.dirname(os.path.realpath(__file__)),
                          *(['..'] * 5 + ['.deps', 'python']))


def import_xacro():
    """The PyPI `xacro` module; falls back to the course repository's .deps/python when the
    caller's environment does not have it on sys.path (workspace sourced without env.sh)."""
    try:
        import xacro
    except ImportError:
        deps = os.path.normpath(_REPO_DEPS)
        if not os.path.isdir(os.path.join(deps, 'xacro')):
            raise
        sys.path.insert(0, deps)
        import xacro
    if not hasattr(xacro, 'process_file'):
        raise ImportError('module xacro at %s is not PyPI xacro 2.x' % getattr(xacro, '__file__', '?'))
    return xacro


class PackageNotFound(Exception):
    """$(find pkg) named a package that rospkg cannot find."""


_rospack = None


def find_package(pkg):
    """Directory of ROS package `pkg` (rospkg, ROS_PACKAGE_PATH), as ROS 1's $(find pkg)."""
    global _rospack
    import rospkg
    if _rospack is None:
        _rospack = rospkg.RosPack()
    try:
        return _rospack.get_path(pkg)
    except rospkg.ResourceNotFound:
        # a package may have been added since the cache was built: ask once more, fresh
        _rospack = rospkg.RosPack()
        try:
            return _rospack.get_path(pkg)
        except rospkg.ResourceNotFound:
            raise PackageNotFound(
                "$(find %s): package '%s' not found on ROS_PACKAGE_PATH "
                "(is the workspace built and sourced?)" % (pkg, pkg)) from None


def install():
    """Make the imported PyPI xacro resolve $(find) through rospkg; returns the xacro module."""
    xacro = import_xacro()
    from xacro import substitution_args as sa

    class FindError(sa.SubstitutionException):
        pass

    def _eval_find(pkg):
        try:
            return find_package(pkg)
        except PackageNotFound as e:
            raise FindError(str(e)) from None

    # `_find` (for $(find)) and `_eval_dict['find']` (for find() inside $(eval)) both use it
    sa._eval_find = _eval_find
    sa._eval_dict['find'] = _eval_find
    return xacro
