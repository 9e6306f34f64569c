"""Generate rosserial client headers (C++) from ROS message and service definitions.

Definitions are read with genmsg straight from the packages' msg/ and srv/ directories (the md5
sums are computed from the same files, exactly as the ROS tools do), so a package needs no
generated Python code to get headers. No rospy.
"""
import os
import shutil
import sys

import genmsg
import genmsg.gentools
import genmsg.msg_loader

# type -> (C++ type, size on the wire, kind)
PRIMITIVES_ARDUINO = {
    'bool': ('bool', 1, 'bool'),
    'byte': ('int8_t', 1, 'int'),
    'int8': ('int8_t', 1, 'int'),
    'char': ('uint8_t', 1, 'uint'),
    'uint8': ('uint8_t', 1, 'uint'),
    'int16': ('int16_t', 2, 'int'),
    'uint16': ('uint16_t', 2, 'uint'),
    'int32': ('int32_t', 4, 'int'),
    'uint32': ('uint32_t', 4, 'uint'),
    'int64': ('int64_t', 8, 'int'),
    'uint64': ('uint64_t', 8, 'uint'),
    'float32': ('float', 4, 'float32'),
    'float64': ('float', 8, 'avrfloat64'),      # AVR: 4-byte float in RAM, 8-byte double on the wire
    'string': ('const char*', None, 'string'),
    'time': ('ros::Time', 8, 'time'),
    'duration': ('ros::Duration', 8, 'time'),
}
PRIMITIVES_GENERIC = dict(PRIMITIVES_ARDUINO, float64=('double', 8, 'float64'))

UNSIGNED = {1: 'uint8_t', 2: 'uint16_t', 4: 'uint32_t', 8: 'uint64_t'}


class Field(object):
    def __init__(self, name, base, is_array, array_len, prim):
        self.name = name
        self.base = base                    # 'uint8', 'std_msgs/Header', ...
        self.is_array = is_array
        self.array_len = array_len          # None for variable-length
        self.prim = prim.get(base)          # None for a nested message
        self.cpp = self.prim[0] if self.prim else base.replace('/', '::')


def _header_dep(base):
    if base == 'time':
        return 'ros/time.h'
    if base == 'duration':
        return 'ros/duration.h'
    return base + '.h'


def _ser_value(expr, f, out):
    """C++ statements serialising the value `expr` of field type f into outbuffer+offset."""
    if f.prim is None:
        return ['offset += %s.serialize(outbuffer + offset);' % expr]
    kind, size = f.prim[2], f.prim[1]
    if kind == 'bool':
        return ['*(outbuffer + offset) = %s ? 1 : 0;' % expr, 'offset += 1;']
    if kind in ('int', 'uint'):
        return ['offset += ros::Msg::serializeUInt<%s>(outbuffer + offset, (%s)(%s));'
                % (UNSIGNED[size], UNSIGNED[size], expr)]
    if kind == 'float32':
        return ['offset += ros::Msg::serializeFloat32(outbuffer + offset, %s);' % expr]
    if kind == 'avrfloat64':
        return ['offset += ros::Msg::serializeAvrFloat64(outbuffer + offset, %s);' % expr]
    if kind == 'float64':
        return ['offset += ros::Msg::serializeFloat64(outbuffer + offset, %s);' % expr]
    if kind == 'string':
        return ['offset += ros::Msg::serializeString(outbuffer + offset, %s);' % expr]
    if kind == 'time':
        return ['offset += ros::Msg::serializeUInt<uint32_t>(outbuffer + offset, (uint32_t)%s.sec);'
                % expr,
                'offset += ros::Msg::serializeUInt<uint32_t>(outbuffer + offset, (uint32_t)%s.nsec);'
                % expr]
    raise ValueError(kind)


def _deser_value(expr, f):
    if f.prim is None:
        return ['offset += %s.deserialize(inbuffer + offset);' % expr]
    kind, size = f.prim[2], f.prim[1]
    if kind == 'bool':
        return ['%s = *(inbuffer + offset) != 0;' % expr, 'offset += 1;']
    if kind in ('int', 'uint'):
        return ['%s = (%s)ros::Msg::deserializeUInt<%s>(inbuffer + offset);'
                % (expr, f.cpp, UNSIGNED[size]), 'offset += %d;' % size]
    if kind == 'float32':
        return ['%s = ros::Msg::deserializeFloat32(inbuffer + offset);' % expr, 'offset += 4;']
    if kind == 'avrfloat64':
        return ['offset += ros::Msg::deserializeAvrFloat64(inbuffer + offset, &(%s));' % expr]
    if kind == 'float64':
        return ['%s = ros::Msg::deserializeFloat64(inbuffer + offset);' % expr, 'offset += 8;']
    if kind == 'string':
        return ['offset += ros::Msg::deserializeString(inbuffer + offset, &(%s));' % expr]
    if kind == 'time':
        t = 'int32_t' if f.base == 'duration' else 'uint32_t'
        return ['%s.sec = (%s)ros::Msg::deserializeUInt<uint32_t>(inbuffer + offset);' % (expr, t),
                '%s.nsec = (%s)ros::Msg::deserializeUInt<uint32_t>(inbuffer + offset + 4);'
                % (expr, t), 'offset += 8;']
    raise ValueError(kind)


def _len_value(expr, f):
    if f.prim is None:
        return '%s.serializedLength()' % expr
    if f.prim[2] == 'string':
        return 'ros::Msg::stringLength(%s)' % expr
    return str(f.prim[1])


def _indent(lines, n):
    return [' ' * n + l for l in lines]


def _constant(c):
    t = c.type
    if t == 'string':
        return 'static constexpr const char* %s = "%s";' % (
            c.name, c.val.replace('\\', '\\\\').replace('"', '\\"'))
    if t in ('float32', 'float64'):
        return 'static constexpr float %s = %r;' % (c.name, float(c.val))
    if t == 'bool':
        return 'enum { %s = %d };' % (c.name, 1 if c.val else 0)
    val = int(c.val)
    suffix = 'ULL' if t.startswith('uint') and val > 0x7FFFFFFF else (
        'LL' if abs(val) > 0x7FFFFFFF else '')
    return 'enum { %s = %d%s };' % (c.name, val, suffix)


def message_class(cls_name, full_type, md5, spec, prim, type_string):
    """C++ class text for one message (spec: genmsg MsgSpec)."""
    fields = []
    for name, typ in zip(spec.names, spec.types):
        base, is_array, array_len = genmsg.msgs.parse_type(typ)
        base = genmsg.msgs.resolve_type(base, spec.package)
        if base == 'Header':
            base = 'std_msgs/Header'
        fields.append(Field(name, base, is_array, array_len, prim))
    lines = (_members(cls_name, fields, spec) + _constructor(cls_name, fields) + _serialize(fields)
             + _deserialize(fields) + _serialized_length(fields))
    lines += ['', '    virtual const char * getType() override { return %s; };' % type_string,
              '    virtual const char * getMD5() override { return "%s"; };' % md5,
              '', '  };']
    return lines, fields


def _members(cls_name, fields, spec):
    lines = ['  class %s : public ros::Msg' % cls_name, '  {', '    public:']
    for f in fields:
        if f.is_array and f.array_len is None:
            lines += ['      uint32_t %s_length;' % f.name,
                      '      typedef %s _%s_type;' % (f.cpp, f.name),
                      '      _%s_type st_%s;' % (f.name, f.name),
                      '      _%s_type * %s;' % (f.name, f.name)]
        elif f.is_array:
            lines += ['      %s %s[%d];' % (f.cpp, f.name, f.array_len)]
        else:
            lines += ['      typedef %s _%s_type;' % (f.cpp, f.name),
                      '      _%s_type %s;' % (f.name, f.name)]
    for c in spec.constants:
        lines.append('      ' + _constant(c))
    return lines


def _constructor(cls_name, fields):
    lines = []
    inits = []
    for f in fields:
        if f.is_array and f.array_len is None:
            inits += ['%s_length(0)' % f.name, 'st_%s()' % f.name, '%s(nullptr)' % f.name]
        elif f.is_array:
            inits.append('%s()' % f.name)
        elif f.prim is not None and f.prim[2] == 'string':
            inits.append('%s("")' % f.name)
        else:
            inits.append('%s()' % f.name)
    lines.append('')
    if inits:
        lines.append('    %s():' % cls_name)
        lines += ['      %s%s' % (i, ',' if k < len(inits) - 1 else '') for k, i in enumerate(inits)]
        lines.append('    {')
        lines.append('    }')
    else:
        lines.append('    %s()' % cls_name)
        lines.append('    {')
        lines.append('    }')
    return lines


def _serialize(fields):
    lines = ['', '    virtual int serialize(unsigned char *outbuffer) const override',
             '    {', '      int offset = 0;']
    for f in fields:
        if f.is_array and f.array_len is None:
            lines += ['      offset += ros::Msg::serializeUInt<uint32_t>(outbuffer + offset, '
                      'this->%s_length);' % f.name,
                      '      for (uint32_t i = 0; i < %s_length; i++) {' % f.name]
            lines += _indent(_ser_value('this->%s[i]' % f.name, f, None), 8)
            lines.append('      }')
        elif f.is_array:
            lines.append('      for (uint32_t i = 0; i < %d; i++) {' % f.array_len)
            lines += _indent(_ser_value('this->%s[i]' % f.name, f, None), 8)
            lines.append('      }')
        else:
            lines += _indent(_ser_value('this->%s' % f.name, f, None), 6)
    return lines + ['      return offset;', '    }']


def _deserialize(fields):
    lines = ['', '    virtual int deserialize(unsigned char *inbuffer) override',
             '    {', '      int offset = 0;']
    for f in fields:
        if f.is_array and f.array_len is None:
            lines += ['      uint32_t %s_lengthT = ros::Msg::deserializeUInt<uint32_t>(inbuffer + offset);'
                      % f.name,
                      '      offset += 4;',
                      '      if (%s_lengthT > %s_length)' % (f.name, f.name),
                      '        this->%s = (_%s_type*)realloc((void*)this->%s, %s_lengthT * sizeof(_%s_type));'
                      % (f.name, f.name, f.name, f.name, f.name),
                      '      %s_length = %s_lengthT;' % (f.name, f.name),
                      '      for (uint32_t i = 0; i < %s_length; i++) {' % f.name]
            lines += _indent(_deser_value('this->st_%s' % f.name, f), 8)
            # a bytewise copy, vtable pointer included: elements live in realloc'd memory
            lines += ['        memcpy((void*)&(this->%s[i]), (const void*)&(this->st_%s), sizeof(_%s_type));'
                      % (f.name, f.name, f.name), '      }']
        elif f.is_array:
            lines.append('      for (uint32_t i = 0; i < %d; i++) {' % f.array_len)
            lines += _indent(_deser_value('this->%s[i]' % f.name, f), 8)
            lines.append('      }')
        else:
            lines += _indent(_deser_value('this->%s' % f.name, f), 6)
    return lines + ['      return offset;', '    }']


def _serialized_length(fields):
    lines = ['', '    virtual int serializedLength() const override', '    {',
             '      int length = 0;']
    for f in fields:
        if f.is_array:
            n = '%s_length' % f.name if f.array_len is None else str(f.array_len)
            if f.array_len is None:
                lines.append('      length += 4;')
            if f.prim is not None and f.prim[2] != 'string':
                lines.append('      length += %s * %s;' % (n, f.prim[1]))
            else:
                lines.append('      for (uint32_t i = 0; i < %s; i++) length += %s;'
                             % (n, _len_value('this->%s[i]' % f.name, f)))
        else:
            lines.append('      length += %s;' % _len_value('this->%s' % f.name, f))
    return lines + ['      return length;', '    }']


def _file(pkg, name, includes, body):
    guard = '_ROS_%s_%s_h' % (pkg, name)
    out = ['#ifndef %s' % guard, '#define %s' % guard, '',
           '#include <stdint.h>', '#include <string.h>', '#include <stdlib.h>',
           '#include "ros/msg.h"']
    out += ['#include "%s"' % i for i in sorted(includes)]
    out += ['', 'namespace %s' % pkg, '{', ''] + body + ['', '}', '#endif', '']
    return '\n'.join(out)


def _includes(fields, own):
    inc = set()
    for f in fields:
        if f.prim is None or f.base in ('time', 'duration'):
            h = _header_dep(f.base)
            if h != own:
                inc.add(h)
    return inc


class Generator(object):
    """Loads and renders every message and service of the packages it is given."""

    def __init__(self, packages, prim=PRIMITIVES_ARDUINO):
        """packages: {name: package directory}."""
        self.packages = packages
        self.prim = prim
        self.search = {}
        for name, path in packages.items():
            d = os.path.join(path, 'msg')
            if os.path.isdir(d):
                self.search[name] = [d]
        self.ctx = genmsg.MsgContext.create_default()

    def message(self, pkg, path):
        name = os.path.basename(path)[:-4]
        full = '%s/%s' % (pkg, name)
        spec = genmsg.msg_loader.load_msg_from_file(self.ctx, path, full)
        genmsg.msg_loader.load_depends(self.ctx, spec, self.search)
        md5 = genmsg.gentools.compute_md5(self.ctx, spec)
        body, fields = message_class(name, full, md5, spec, self.prim, '"%s"' % full)
        return _file(pkg, name, _includes(fields, full + '.h'), body)

    def service(self, pkg, path):
        name = os.path.basename(path)[:-4]
        full = '%s/%s' % (pkg, name)
        spec = genmsg.msg_loader.load_srv_from_file(self.ctx, path, full)
        genmsg.msg_loader.load_depends(self.ctx, spec, self.search)
        const = name.upper()
        body = ['static const char %s[] = "%s";' % (const, full), '']
        fields = []
        for part, sub in (('Request', spec.request), ('Response', spec.response)):
            md5 = genmsg.gentools.compute_md5(self.ctx, sub)
            lines, f = message_class(name + part, full, md5, sub, self.prim, const)
            body += lines + ['']
            fields += f
        body += ['  class %s {' % name, '    public:',
                 '    typedef %sRequest Request;' % name,
                 '    typedef %sResponse Response;' % name, '  };']
        return _file(pkg, name, _includes(fields, full + '.h'), body)

    def generate(self, out_dir, log=print):
        """Write <out_dir>/<pkg>/<Type>.h for every msg and srv; return the failed types."""
        failed = []
        for pkg in sorted(self.packages):
            path = self.packages[pkg]
            for kind, render in (('msg', self.message), ('srv', self.service)):
                d = os.path.join(path, kind)
                if not os.path.isdir(d):
                    continue
                for fn in sorted(os.listdir(d)):
                    if not fn.endswith('.' + kind):
                        continue
                    try:
                        text = render(pkg, os.path.join(d, fn))
                    except Exception as e:
                        log('Unable to build message: %s/%s (%s)' % (pkg, fn[:-4], e))
                        failed.append('%s/%s' % (pkg, fn[:-4]))
                        continue
                    os.makedirs(os.path.join(out_dir, pkg), exist_ok=True)
                    with open(os.path.join(out_dir, pkg, fn[:-4] + '.h'), 'w') as f:
                        f.write(text)
        return failed


def visible_packages():
    """{name: path} of every package rospack sees that has msg/ or srv/ definitions."""
    import rospkg
    rp = rospkg.RosPack()
    out = {}
    for name in rp.list():
        path = rp.get_path(name)
        if os.path.isdir(os.path.join(path, 'msg')) or os.path.isdir(os.path.join(path, 'srv')):
            out[name] = path
    return out


def core_dir():
    """rosserial_client's own ros_lib sources (ros/*.h, time.cpp, duration.cpp, tf/*)."""
    here = os.path.dirname(os.path.abspath(__file__))
    cand = os.path.join(here, '..', 'ros_lib')
    if os.path.isdir(cand):
        return os.path.normpath(cand)
    import rospkg
    return os.path.join(rospkg.RosPack().get_path('rosserial_client'), 'src', 'ros_lib')


def make_library(out_dir, extra_dirs=(), prim=PRIMITIVES_ARDUINO, packages=None, log=print):
    """Build a complete ros_lib in out_dir (deleted first). extra_dirs are copied over the
    core (the platform's ros.h, hardware header, examples). Returns the failed types."""
    if os.path.exists(out_dir):
        shutil.rmtree(out_dir)
    shutil.copytree(core_dir(), out_dir)
    for d in extra_dirs:
        for root, _, files in os.walk(d):
            rel = os.path.relpath(root, d)
            os.makedirs(os.path.join(out_dir, rel), exist_ok=True)
            for fn in files:
                shutil.copy(os.path.join(root, fn), os.path.join(out_dir, rel, fn))
    if packages is None:
        packages = visible_packages()
    return Generator(packages, prim).generate(out_dir, log)


def main(argv, prim, extra_dirs=(), prog='make_libraries'):
    if len(argv) != 1 or argv[0].startswith('-'):
        sys.stderr.write('usage: %s <output directory>  (ros_lib is created inside it)\n' % prog)
        return 2
    out = os.path.join(os.path.abspath(argv[0]), 'ros_lib')
    parent = os.path.dirname(out)
    if os.path.exists(parent) and not os.path.isdir(parent):
        sys.stderr.write('%s: %s exists and is not a directory\n' % (prog, argv[0]))
        return 2
    try:
        os.makedirs(parent, exist_ok=True)   # as the original (copytree): a missing OUTPUT is made
    except OSError as e:
        sys.stderr.write('%s: cannot create %s: %s\n' % (prog, argv[0], e.strerror or e))
        return 2
    print('\nExporting to %s' % out)
    failed = make_library(out, extra_dirs, prim)
    n = sum(len(fs) for _, _, fs in os.walk(out))
    print('Wrote %d files to %s' % (n, out))
    if failed:
        pkgs = sorted(set(f.split('/')[0] for f in failed))
        print('Failed to build %d messages of the packages: %s' % (len(failed), ', '.join(pkgs)))
        return 1
    return 0


# -- the original make_library's module API, for scripts written against it ------------------
# (rosserial_test's generate_client_ros_lib.py, board packages' make_libraries scripts):
#   from rosserial_client.make_library import *
#   rosserial_client_copy_files(rospack, path + '/')
#   rosserial_generate(rospack, path, {'float64': ('float', 8, AVR_Float64DataType, []), ...})
# The mapping's entries are (C++ type, size, data type class, includes); the wire sizes are the
# ROS ones whatever the size says, the C++ type is taken from the mapping.

class PrimitiveDataType(object):
    """Marker of the original's data type classes (only their identity is used here)."""


class MessageDataType(PrimitiveDataType):
    pass


class AVR_Float64DataType(PrimitiveDataType):
    pass


class Float64DataType(PrimitiveDataType):
    pass


class StringDataType(PrimitiveDataType):
    pass


class TimeDataType(PrimitiveDataType):
    pass


class ArrayDataType(PrimitiveDataType):
    pass


def primitives_from_mapping(mapping):
    """The original's ROS_TO_EMBEDDED_TYPES mapping -> this generator's primitives table."""
    prim = dict(PRIMITIVES_GENERIC)
    for ros_type, entry in mapping.items():
        if ros_type not in prim:
            continue                      # 'Header' and other message types: generated as such
        cpp, cls = entry[0], entry[2]
        if ros_type == 'float64':
            if cls is AVR_Float64DataType or cpp == 'float':
                prim[ros_type] = ('float', 8, 'avrfloat64')
            else:
                prim[ros_type] = (cpp, 8, 'float64')
        elif ros_type == 'string':
            prim[ros_type] = ('const char*', None, 'string')
        else:
            _, size, kind = prim[ros_type]
            prim[ros_type] = (cpp, size, kind)
    return prim


def rosserial_client_copy_files(rospack, path):
    """Copy rosserial_client's own ros_lib sources (ros/*.h, time.cpp, duration.cpp, tf/*)
    into path, creating it."""
    src = core_dir()
    for root, _, files in os.walk(src):
        rel = os.path.relpath(root, src)
        os.makedirs(os.path.join(path, rel), exist_ok=True)
        for fn in files:
            shutil.copy(os.path.join(root, fn), os.path.join(path, rel, fn))


def rosserial_generate(rospack, path, mapping):
    """One header per message and service of every package `rospack` sees, into path;
    returns the types that could not be generated (printed as the original does)."""
    packages = {}
    for name in rospack.list():
        p = rospack.get_path(name)
        if os.path.isdir(os.path.join(p, 'msg')) or os.path.isdir(os.path.join(p, 'srv')):
            packages[name] = p
    failed = Generator(packages, primitives_from_mapping(mapping)).generate(path, print)
    if failed:
        print('*** Warning, failed to generate libraries for the following packages: ***')
        for f in sorted(set(x.split('/')[0] for x in failed)):
            print('    %s' % f)
    return failed
