#!/usr/bin/python3
"""rostest checker of lab 1: observe the student's three nodes, write a per-criterion report."""
from grading import lab1
from grading.checker import run_checker
from grading.lab1 import observer, rules

if __name__ == '__main__':
    run_checker(lab1, rules, observer.observe)
