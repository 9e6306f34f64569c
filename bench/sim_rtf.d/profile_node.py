#!/usr/bin/python3
"""sim_node under cProfile timed by the CPU time of its simulation thread (time.thread_time),
so a loaded machine does not distort the shares: profile_node.py OUT.prof [sim_node args]."""
import cProfile
import sys
import time


def main():
    out = sys.argv.pop(1)
    from ode_sim.ros.cli import main as sim_main
    prof = cProfile.Profile(time.thread_time)
    try:
        prof.runcall(sim_main, sys.argv)
    finally:
        prof.dump_stats(out)


if __name__ == '__main__':
    main()
