"""The `xacro` command of ROS 1 on top of the PyPI xacro 2.1.1 module.

Options and `name:=value` arguments are parsed by PyPI xacro's own parser (the same surface as
ROS 1's xacro 1.14: -o FILE, --deps, --inorder/-i, -q, -v, --verbosity N, --root-dir DIR).
`$(find)` is resolved through rospkg (see resolve.py). Errors are reported as one line
`xacro: error: FILE[:LINE]: what` on stderr with exit code 2 (the original's error code);
`-v -v` (verbosity >= 2) re-raises for a stack trace, as the original does.
"""
import os
import re
import sys
import xml.parsers.expat

from xacro_ros.resolve import install

EXIT_ERROR = 2


class XacroError(Exception):
    """A failed expansion, with the file (and line when known) it happened in."""

    def __init__(self, what, filename=None, line=None, column=None):
        super().__init__(what)
        self.what = what
        self.filename = filename
        self.line = line
        self.column = column

    def __str__(self):
        where = self.filename or '<input>'
        if self.line:
            where += ':%d' % self.line
            if self.column is not None:
                where += ':%d' % self.column
        return '%s: %s' % (where, self.what)


def _load():
    try:
        return install()
    except ImportError as e:
        raise XacroError('cannot import the PyPI xacro module (%s); run scripts/setup.sh and '
                         'source scripts/env.sh' % e, 'xacro') from None


def expand(input_file, mappings=None, verbosity=1, root_dir=None):
    """Expand `input_file`; returns the xml.dom Document (with xacro's banner).
    Raises XacroError with a located one-line message on any failure."""
    xacro = _load()
    xacro.all_includes = []
    if root_dir:
        xacro.root_dir = root_dir
    xacro.init_stacks(input_file)
    try:
        return xacro.process_file(input_file, mappings=dict(mappings or {}), verbosity=verbosity)
    except RecursionError:
        raise XacroError('recursion too deep (a macro or include that calls itself?)',
                         *_where(xacro, input_file, None)) from None
    except (xml.parsers.expat.ExpatError, xacro.XacroException, Exception) as e:
        if verbosity > 1:
            raise
        raise describe(xacro, e, input_file) from None
    finally:
        xacro.substitution_args_context['arg'] = {}


def expand_to_string(input_file, mappings=None, verbosity=1):
    """Expanded URDF/XML text, pretty-printed as the xacro command writes it."""
    return expand(input_file, mappings, verbosity).toprettyxml(indent='  ')


def dependencies(input_file, mappings=None):
    """Files included (directly or not) by input_file, in order of inclusion."""
    xacro = _load()
    expand(input_file, mappings)
    seen = []
    for f in xacro.all_includes:
        if f not in seen:
            seen.append(f)
    return seen


def _current_file(xacro, input_file):
    """The file being processed when the error happened (a macro's own file inside a macro)."""
    if xacro.macrostack:
        hist = xacro.macrostack[-1].history
        if hist and hist[-1] and hist[-1][-1]:
            return hist[-1][-1]
    if xacro.filestack and xacro.filestack[-1]:
        return xacro.filestack[-1]
    return input_file


def _where(xacro, input_file, pattern):
    filename = _current_file(xacro, input_file)
    return filename, (_find_line(filename, pattern) if pattern else None)


def _find_line(filename, pattern):
    """Line number (1-based) of the first line matching regex `pattern`, or None."""
    try:
        with open(filename, encoding='utf-8', errors='replace') as f:
            for n, text in enumerate(f, 1):
                if re.search(pattern, text):
                    return n
    except OSError:
        pass
    return None


def _one_line(text):
    return ' '.join(str(text).split())


def describe(xacro, e, input_file):
    """Turn an exception of PyPI xacro into a located XacroError."""
    from xacro import substitution_args as sa
    if isinstance(e, xml.parsers.expat.ExpatError):
        filename = xacro.filestack[-1] if xacro.filestack and xacro.filestack[-1] else input_file
        return XacroError('malformed XML: %s' % xml.parsers.expat.ErrorString(e.code),
                          filename, e.lineno, e.offset)
    if not isinstance(e, xacro.XacroException):
        return XacroError('%s: %s' % (type(e).__name__, _one_line(e)),
                          *_where(xacro, input_file, None))

    inner = e.exc
    base = _one_line(super(xacro.XacroException, e).__str__() or '')
    expr = None
    if e.suffix:
        m = re.search(r"when evaluating expression '(.*)'", str(e.suffix), re.S)
        expr = m.group(1) if m else None

    if isinstance(inner, NameError):
        name = getattr(inner, 'name', None) or re.search(r"'([^']*)'", str(inner)).group(1)
        what = "undefined property or name '%s'" % name
        if expr is not None:
            what += " in expression '${%s}'" % _one_line(expr)
        return XacroError(what, *_where(xacro, input_file, r'\$\{[^}]*\b%s\b' % re.escape(name)))
    if isinstance(inner, sa.ArgException):
        name = str(inner)
        return XacroError("undefined substitution argument '%s' (give %s:=VALUE on the command "
                          "line or declare <xacro:arg name=\"%s\" default=\"...\"/>)" % (name, name, name),
                          *_where(xacro, input_file, r'\$\(arg\s+%s\s*\)' % re.escape(name)))
    if isinstance(inner, sa.SubstitutionException):
        msg = _one_line(inner)
        m = re.match(r"\$\(find (\S+)\)", msg)
        pattern = r'\$\(find\s+%s\s*\)' % re.escape(m.group(1)) if m else None
        return XacroError(msg, *_where(xacro, input_file, pattern))
    if isinstance(inner, (IOError, OSError)) and getattr(inner, 'filename', None):
        missing = inner.filename
        # the including file is on top of the stack again (xacro pops the missing one)
        including = xacro.filestack[-1] if xacro.filestack and xacro.filestack[-1] else None
        if including is None or os.path.abspath(missing) == os.path.abspath(input_file):
            return XacroError('cannot open file: %s' % (inner.strerror or inner), input_file)
        pat = r'<xacro:include\b[^>]*%s' % re.escape(os.path.basename(missing))
        return XacroError('cannot include %s: %s' % (missing, inner.strerror or inner),
                          including, _find_line(including, pat))
    m = re.match(r'unknown macro name: (\S+)', base)
    if m:
        tag = m.group(1)
        return XacroError('unknown macro %s (not defined or not included before use)' % tag,
                          *_where(xacro, input_file, r'<%s\b' % re.escape(tag)))

    what = base
    if inner is not None:
        detail = '%s: %s' % (type(inner).__name__, _one_line(inner))
        what = detail if base.startswith('<class') or not base else '%s %s' % (base, detail)
    if expr is not None:
        what += " in expression '${%s}'" % _one_line(expr)
    macro = xacro.macrostack[-1].body.getAttribute('name') if xacro.macrostack else None
    pattern = None
    if macro:
        what += " (in macro '%s')" % macro
    return XacroError(what, *_where(xacro, input_file, pattern))


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    try:
        xacro = _load()
    except XacroError as e:
        print('xacro: error: %s' % e, file=sys.stderr)
        return EXIT_ERROR
    try:
        opts, input_file = xacro.cli.process_args(argv)
    except RuntimeError as e:                     # an invalid name:=value argument
        print('xacro: error: %s' % _one_line(e), file=sys.stderr)
        return EXIT_ERROR
    verbosity = opts.verbosity if opts.verbosity is not None else 1
    try:
        doc = expand(input_file, opts.mappings, verbosity, opts.root_dir)
    except XacroError as e:
        print('xacro: error: %s' % e, file=sys.stderr)
        return EXIT_ERROR
    if opts.just_deps:
        seen = []
        for f in xacro.all_includes:
            if f not in seen:
                seen.append(f)
        text = ' '.join(seen)
    else:
        text = doc.toprettyxml(indent='  ')
    try:
        if opts.output:
            d = os.path.dirname(opts.output)
            if d:
                os.makedirs(d, exist_ok=True)
            with open(opts.output, 'w') as f:
                f.write(text)
        else:
            sys.stdout.write(text)
            sys.stdout.flush()
    except BrokenPipeError:
        sys.stderr.close()
        return 0
    except OSError as e:
        print('xacro: error: %s: cannot write output: %s' % (opts.output, e.strerror or e),
              file=sys.stderr)
        return EXIT_ERROR
    return 0
