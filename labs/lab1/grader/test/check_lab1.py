#!/usr/bin/python3
"""rostest checker of lab 1: observe the student's three nodes, write a per-criterion report."""
from grading import lab1
from grading.checker import run_checker
from grading.observe import Lab1Observer


def observe(isu, pkg_dir, workdir):
    return Lab1Observer(isu, lab1.node_scripts(pkg_dir), workdir).run()


if __name__ == '__main__':
    run_checker('lab1', lab1, observe)
