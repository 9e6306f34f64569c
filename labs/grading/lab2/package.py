"""Static checks of the student's lab 2 package: its launch files and scripts (no rospy)."""
import ast
import os
import re
import xml.etree.ElementTree as ET

from grading.lab2.criteria import LAUNCH


def launch_files(pkg_dir):
    out = []
    for d, dirs, files in os.walk(pkg_dir):
        dirs[:] = [x for x in dirs if not x.startswith('.') and x not in ('build', 'devel')]
        out += [os.path.join(d, f) for f in files if f.endswith('.launch') or f.endswith('.launch.xml')]
    return sorted(out)


def find_launch(pkg_dir):
    for f in launch_files(pkg_dir):
        if os.path.basename(f) == LAUNCH:
            return f
    return None


def declares_isu(path):
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError):
        return False
    return any(a.get('name') == 'isu' for a in root.findall('arg'))


def remaps(pkg_dir):
    """['file: <remap from=a to=b>' ...] for every remap in the package's launch files."""
    found = []
    for f in launch_files(pkg_dir):
        rel = os.path.relpath(f, pkg_dir)
        try:
            root = ET.parse(f).getroot()
        except ET.ParseError as e:
            found.append('%s: unreadable (%s)' % (rel, e))
            continue
        for el in root.iter('remap'):
            found.append('%s: <remap from="%s" to="%s"/>' % (rel, el.get('from'), el.get('to')))
        for el in root.iter('node'):
            for a in (el.get('args') or '').split():
                if ':=' in a and not a.startswith('_'):
                    found.append('%s: node %s args %s' % (rel, el.get('name'), a))
    return found


GLOBAL_NAME = re.compile(r'^/[A-Za-z][A-Za-z0-9_]*(/[A-Za-z0-9_]+)*/?$')


def global_literals(pkg_dir):
    """['file:line "/name"'] for string literals that look like global ROS names."""
    found = []
    for d, dirs, files in os.walk(pkg_dir):
        dirs[:] = [x for x in dirs if not x.startswith('.') and x not in ('build', 'devel', 'test')]
        for f in files:
            if not f.endswith('.py') or f == 'setup.py':
                continue
            p = os.path.join(d, f)
            try:
                with open(p, errors='replace') as fh:
                    tree = ast.parse(fh.read(), p)
            except (SyntaxError, OSError, ValueError):
                continue
            docstrings = {id(n.value) for n in ast.walk(tree) if isinstance(n, ast.Expr)}
            for n in ast.walk(tree):
                if isinstance(n, ast.Constant) and isinstance(n.value, str) and id(n) not in docstrings:
                    v = n.value
                    if v.startswith('/') and GLOBAL_NAME.match(v.split('{')[0].rstrip('_') or v):
                        if not v.startswith(('/usr', '/tmp', '/dev', '/home', '/opt', '/etc', '/proc')):
                            found.append('%s:%d "%s"' % (os.path.relpath(p, pkg_dir), n.lineno, v))
    return found
