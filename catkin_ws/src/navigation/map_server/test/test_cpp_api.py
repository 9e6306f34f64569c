"""map_server's C++ API as a user's package uses it: an overlay workspace whose package only
says find_package(catkin REQUIRED COMPONENTS map_server), includes map_server/image_loader.h and
links ${catkin_LIBRARIES} builds with catkin_make and loads the test map."""
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from make_fixtures import TESTMAP  # noqa: E402

CMAKE = '''cmake_minimum_required(VERSION 3.0.2)
project(map_user)
find_package(catkin REQUIRED COMPONENTS map_server)
catkin_package()
include_directories(${catkin_INCLUDE_DIRS})
add_executable(load_map src/load_map.cpp)
target_link_libraries(load_map ${catkin_LIBRARIES})
'''
PACKAGE = '''<?xml version="1.0"?>
<package format="2"><name>map_user</name><version>0.0.1</version><description>uses map_server</description>
  <maintainer email="user@example.org">user</maintainer><license>BSD</license>
  <buildtool_depend>catkin</buildtool_depend><depend>map_server</depend></package>
'''
MAIN = '''#include <map_server/image_loader.h>
#include <cstdio>
int main(int, char** argv) {
  nav_msgs::GetMap::Response r;
  double origin[3] = {1.0, 2.0, 0.0};
  map_server::loadMapFromFile(&r, argv[1], 0.05, false, 0.65, 0.196, origin, TRINARY);
  std::printf("%u %u %g", r.map.info.width, r.map.info.height, r.map.info.origin.position.x);
  for (signed char v : r.map.data) std::printf(" %d", v);
  return 0;
}
'''


def test_an_overlay_package_builds_and_loads_a_map(tmp_path):
    pkg = tmp_path / 'src' / 'map_user'
    (pkg / 'src').mkdir(parents=True)
    (pkg / 'CMakeLists.txt').write_text(CMAKE)
    (pkg / 'package.xml').write_text(PACKAGE)
    (pkg / 'src' / 'load_map.cpp').write_text(MAIN)
    build = subprocess.run(['catkin_make', '-C', str(tmp_path), '-DPYTHON_EXECUTABLE=/usr/bin/python3'],
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=600)
    assert build.returncode == 0, build.stdout[-3000:]
    run = subprocess.run([str(tmp_path / 'devel' / 'lib' / 'map_user' / 'load_map'),
                          os.path.join(HERE, 'testmap.png')], capture_output=True, text=True, timeout=60)
    assert run.returncode == 0, run.stderr
    w, h, x, *cells = run.stdout.split()
    assert (w, h, float(x)) == ('10', '10', 1.0)
    assert [int(v) for v in cells] == [v for row in TESTMAP for v in row]
