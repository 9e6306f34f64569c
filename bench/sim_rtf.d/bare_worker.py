#!/usr/bin/python3
"""sim_rtf --launch's bare C loop in a process (and session) of its own, so that on a shared
machine it gets the scheduler's share the launch's nodes get (with autogroup scheduling every
session is one group: a loop inside the measuring tool's session would share that session's
part with everything else started there).

bare_worker.py LIB WORLD URDF: builds the scene once (bench/sim_rtf bare_c_runner), prints
`ready`, then for each line STEPS on stdin runs that many steps and prints
`SIM_PER_WALL SIM_PER_CPU`; exits at end of input."""
import os
import sys
from importlib.machinery import SourceFileLoader

HERE = os.path.dirname(os.path.abspath(__file__))


def main(argv):
    lib, world, urdf = argv[1:4]
    bench = SourceFileLoader('sim_rtf_bench', os.path.join(os.path.dirname(HERE), 'sim_rtf'))
    run = bench.load_module().bare_c_runner(lib, world, urdf)
    print('ready', flush=True)
    for line in sys.stdin:
        wall, cpu = run(int(line))
        print('%.6f %.6f' % (wall, cpu), flush=True)
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
