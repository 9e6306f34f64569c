"""Practical work 7 replayed as a student does it: `rosrun rosserial_arduino make_libraries.py`
into a sketchbook, `firmware/build` of the starter sketches against that ros_lib (HelloWorld
complete, Blink and ultrasound with their TODOs still compile), and (full run only) HelloWorld
on the emulated Mega bridged by `serial_node.py` to `rostopic echo /chatter`. The gate's
end-to-end runs of all three reference sketches are in rosserial_arduino/test/test_firmware_hil.py."""
import os
import shutil
import subprocess
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
STARTER = os.path.join(HERE, 'task_7', 'starter')
BUILD = os.path.join(REPO, 'firmware', 'build')


@pytest.fixture(scope='module')
def sketchbook(tmp_path_factory):
    book = tmp_path_factory.mktemp('sketchbook')
    libs = book / 'libraries'
    libs.mkdir()
    p = subprocess.run(['rosrun', 'rosserial_arduino', 'make_libraries.py', str(libs)],
                       capture_output=True, text=True, timeout=300)
    assert p.returncode == 0, p.stdout[-2000:] + p.stderr[-2000:]
    assert 'Exporting to %s' % (libs / 'ros_lib') in p.stdout
    for f in ('ros.h', 'ArduinoHardware.h', 'ros/node_handle.h', 'std_msgs/String.h',
              'sensor_msgs/Range.h', 'rosserial_msgs/TopicInfo.h', 'rosserial_arduino/Adc.h'):
        assert (libs / 'ros_lib' / f).is_file(), f
    for name in ('hello_world', 'blink', 'ultrasound'):
        shutil.copytree(os.path.join(STARTER, name), str(book / name))
    return book


@pytest.mark.parametrize('sketch', ['hello_world',
                                    pytest.param('blink', marks=pytest.mark.full),
                                    pytest.param('ultrasound', marks=pytest.mark.full)])
def test_starter_builds_for_the_mega(sketchbook, sketch):
    out = sketchbook / ('build_' + sketch)
    p = subprocess.run([BUILD, str(sketchbook / sketch), '--ros-lib',
                        str(sketchbook / 'libraries' / 'ros_lib'), '--out', str(out)],
                       capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-3000:]
    lines = p.stdout.strip().splitlines()
    assert lines[-1] == str(out / (sketch + '.elf'))
    assert 'atmega2560' in p.stdout and 'Program:' in p.stdout
    assert 'warning' not in p.stdout.lower() or sketch != 'hello_world', p.stdout
    assert (out / (sketch + '.hex')).is_file()


@pytest.mark.full
def test_hello_world_on_the_emulated_mega(sketchbook, roscore, tmp_path):
    sys.path.insert(0, os.path.join(REPO, 'firmware', 'hil'))
    import harness
    from course_testing import Proc, wait_for
    out = sketchbook / 'build_run'
    elf = subprocess.run([BUILD, str(sketchbook / 'hello_world'), '--ros-lib',
                          str(sketchbook / 'libraries' / 'ros_lib'), '--out', str(out)],
                         capture_output=True, text=True, timeout=600).stdout.split()[-1]
    with harness.Simulation(elf) as sim:
        node = Proc(['rosrun', 'rosserial_python', 'serial_node.py', sim.pty], env=roscore.env,
                    log=str(tmp_path / 'node.log'))
        try:
            wait_for(lambda: 'Setup publisher on chatter' in node.output(), 120,
                     what='negotiation:\n' + node.output())
            p = subprocess.run(['rostopic', 'echo', '-n', '1', '/chatter'], env=roscore.env,
                               capture_output=True, text=True, timeout=120)
            assert 'data: "hello world!"' in p.stdout
        finally:
            node.stop()


def test_memory_report_without_avr_size_c(sketchbook):
    """firmware/build's own "AVR Memory Usage" report (for Debian 13's avr-size, which has no
    -C) says what avr-size -C says where it has it, and sums the sections otherwise."""
    import importlib.machinery
    import importlib.util
    loader = importlib.machinery.SourceFileLoader('firmware_build', BUILD)
    spec = importlib.util.spec_from_loader('firmware_build', loader)
    build = importlib.util.module_from_spec(spec)
    loader.exec_module(build)
    out = sketchbook / 'build_report'
    p = subprocess.run([BUILD, str(sketchbook / 'hello_world'), '--ros-lib',
                        str(sketchbook / 'libraries' / 'ros_lib'), '--out', str(out)],
                       capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-3000:]
    elf = str(out / 'hello_world.elf')
    report = build.memory_usage(elf)
    assert 'Device: atmega2560' in report and 'Program:' in report and 'Data:' in report
    c = subprocess.run(['avr-size', '--mcu=atmega2560', '-C', elf], capture_output=True, text=True)
    if c.returncode == 0:       # Debian 12's binutils-avr: the same report, line for line
        def words(t):
            return [line.split() for line in t.splitlines() if line.strip()]
        assert words(report) == words(c.stdout)
    berkeley = subprocess.run(['avr-size', elf], capture_output=True, text=True).stdout.split()
    text, data, bss = (int(v) for v in berkeley[6:9])
    assert 'Program: %7d bytes' % (text + data) in report
    assert 'Data:    %7d bytes' % (data + bss) in report
