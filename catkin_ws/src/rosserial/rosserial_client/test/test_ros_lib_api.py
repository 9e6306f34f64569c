"""ros_lib's Time / Duration arithmetic and comparisons, the AVR float64 round trip and the
subscriber callbacks: a gtest program built with the host's g++ against rosserial_client's
sources (-Wall -Wextra -Werror, AddressSanitizer) and run."""
import os
import shutil
import subprocess

import rospkg

from rosserial_client.make_library import PRIMITIVES_GENERIC, core_dir, make_library

HERE = os.path.dirname(os.path.abspath(__file__))


def test_ros_lib_api_gtest(tmp_path):
    rp = rospkg.RosPack()
    lib = str(tmp_path / 'ros_lib')
    # the generated rosserial_msgs headers subscriber.h includes
    assert make_library(lib, [], PRIMITIVES_GENERIC,
                        packages={'rosserial_msgs': rp.get_path('rosserial_msgs')}) == []
    gxx = shutil.which('g++')
    assert gxx, 'g++ is missing (Debian package g++)'
    exe = str(tmp_path / 'api_test')
    src = core_dir()
    cmd = [gxx, '-std=c++17', '-Wall', '-Wextra', '-Werror', '-Wno-unused-parameter',
           '-fsanitize=address,undefined', '-fno-sanitize-recover=undefined', '-I', src, '-I', lib,
           os.path.join(HERE, 'ros_lib_api_test.cpp'), os.path.join(src, 'time.cpp'),
           os.path.join(src, 'duration.cpp'), '-lgtest', '-pthread', '-o', exe]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr[-4000:]
    p = subprocess.run([exe], capture_output=True, text=True, timeout=60)
    assert p.returncode == 0, p.stdout[-4000:] + p.stderr[-2000:]
    assert '[  PASSED  ] 8 tests' in p.stdout, p.stdout[-2000:]


def test_make_libraries_creates_a_missing_output_directory(tmp_path, monkeypatch, capsys):
    """`make_libraries OUTPUT` with OUTPUT (and its parents) missing makes them, as the
    original (which copies the library in with copytree); a file in the way is one error line."""
    import rosserial_client.make_library as ml
    rp = rospkg.RosPack()
    monkeypatch.setattr(ml, 'visible_packages',
                        lambda: {'std_msgs': rp.get_path('std_msgs'),
                                 'rosserial_msgs': rp.get_path('rosserial_msgs')})
    out = tmp_path / 'sketchbook' / 'libraries'
    assert ml.main([str(out)], PRIMITIVES_GENERIC) == 0
    assert (out / 'ros_lib' / 'std_msgs' / 'String.h').is_file()
    assert (out / 'ros_lib' / 'ros' / 'node_handle.h').is_file()
    blocker = tmp_path / 'afile'
    blocker.write_text('x')
    assert ml.main([str(blocker)], PRIMITIVES_GENERIC) == 2
    assert 'exists and is not a directory' in capsys.readouterr().err
