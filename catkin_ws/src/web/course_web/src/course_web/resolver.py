"""Maps request paths to files: the page's own files and package:// resources.

No ROS imports: the package lookup is a callable handed in by the node (rospkg in
practice, a dict in the unit tests). Nothing outside the www directory or a package's
directory is ever returned: '..', absolute parts, NUL bytes and symlinks that leave the
root are all refused.
"""
import os
import re
from urllib.parse import unquote, urlsplit

_PKG_NAME = re.compile(r'^[A-Za-z][A-Za-z0-9_]*$')

PACKAGE_PREFIX = '/package/'


class ResolveError(Exception):
    """A request that maps to no servable file. `status` is the HTTP status to answer."""

    def __init__(self, status, reason):
        super().__init__(reason)
        self.status = status
        self.reason = reason


def safe_join(root, relpath):
    """The real path of `relpath` inside `root`, or ResolveError(403/404).

    `relpath` is a URL path already percent-decoded; it must stay inside `root` after
    every symlink is resolved."""
    if '\0' in relpath:
        raise ResolveError(400, 'NUL byte in path')
    parts = [p for p in relpath.replace('\\', '/').split('/') if p not in ('', '.')]
    if any(p == '..' for p in parts):
        raise ResolveError(403, "'..' in path")
    root_real = os.path.realpath(root)
    target = os.path.realpath(os.path.join(root_real, *parts)) if parts else root_real
    if target != root_real and not target.startswith(root_real + os.sep):
        raise ResolveError(403, 'path leaves %s' % root)
    if not os.path.exists(target):
        raise ResolveError(404, 'no such file: %s' % relpath)
    return target


def package_url_to_http(url):
    """'package://pkg/path' -> '/package/pkg/path' (the form the page requests)."""
    if not url.startswith('package://'):
        raise ResolveError(400, 'not a package:// URL: %s' % url)
    return PACKAGE_PREFIX + url[len('package://'):]


def resolve_package(pkg_and_path, find_package):
    """'pkg/some/file.stl' -> the file's real path inside package `pkg`.

    find_package(name) returns the package's directory or raises (any exception means
    unknown package)."""
    pkg, _, rel = pkg_and_path.partition('/')
    if not _PKG_NAME.match(pkg):
        raise ResolveError(400, 'bad package name: %r' % pkg)
    try:
        root = find_package(pkg)
    except Exception:  # rospkg.ResourceNotFound, KeyError in tests: both mean "no such package"
        raise ResolveError(404, 'unknown package: %s' % pkg)
    if not rel:
        raise ResolveError(403, 'a package directory is not served: %s' % pkg)
    path = safe_join(root, rel)
    if os.path.isdir(path):
        raise ResolveError(403, 'directories are not listed: %s' % pkg_and_path)
    return path


def resolve(request_path, www_root, find_package):
    """Any request path of the page -> a file path (ResolveError when there is none)."""
    path = unquote(urlsplit(request_path).path)
    if path.startswith(PACKAGE_PREFIX):
        return resolve_package(path[len(PACKAGE_PREFIX):], find_package)
    if path in ('', '/'):
        path = '/index.html'
    target = safe_join(www_root, path)
    if os.path.isdir(target):
        target = safe_join(target, 'index.html')
    return target
