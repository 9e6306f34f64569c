"""view_frames without ROS: write frames.gv and turn it into frames.pdf with graphviz's dot,
as tf's view_frames does (its graphviz version check, Python 3 safe: text, no distutils)."""
import re
import subprocess
import sys

MIN_PDF_VERSION = (2, 8)      # older dot cannot write PDF: the original writes PostScript then
_VERSION = re.compile(r'.*version (\d+\.?\d*)')


def dot_version(text):
    """(major, minor) from `dot -V` output ('dot - graphviz version 2.43.0 (0)'), or None."""
    if isinstance(text, bytes):
        text = text.decode('utf-8', 'replace')
    m = _VERSION.search(text or '')
    if not m or not m.group(1):
        return None
    parts = m.group(1).split('.')
    return int(parts[0]), int(parts[1]) if len(parts) > 1 and parts[1] else 0


def generate(dot_graph, run=subprocess.run, out=print, err=None):
    """Write frames.gv in the current directory and render frames.pdf (frames.ps with a dot
    older than 2.8). Returns the exit status: 0, 255 when dot is missing (the original's
    sys.exit(-1)), 1 when dot fails."""
    err = err or (lambda msg: print(msg, file=sys.stderr))
    with open('frames.gv', 'w') as outfile:
        outfile.write(dot_graph)
    try:
        vstr = run(['dot', '-V'], stdout=subprocess.PIPE, stderr=subprocess.PIPE).stderr
    except OSError:
        out('Warning: Could not execute `dot -V`.  Is graphviz installed?')
        return 255
    vstr = vstr.decode('utf-8', 'replace') if isinstance(vstr, bytes) else (vstr or '')
    out(vstr.strip())
    version = dot_version(vstr)
    if version is None:
        out('Warning: failed to determine your version of dot.  Assuming v2.16')
        version = (2, 16)
    else:
        out('Detected dot version {}.{}'.format(*version))
    if version > MIN_PDF_VERSION:
        cmd, name = ['dot', '-Tpdf', 'frames.gv', '-o', 'frames.pdf'], 'frames.pdf'
    else:
        cmd, name = ['dot', '-Tps2', 'frames.gv', '-o', 'frames.ps'], 'frames.ps'
    if run(cmd).returncode != 0:
        err('failed to generate frames.pdf')
        return 1
    out('{} generated'.format(name))
    return 0
