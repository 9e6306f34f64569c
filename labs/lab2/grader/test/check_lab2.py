#!/usr/bin/python3
"""rostest checker of lab 2: observe the student's launch file, write a per-criterion report."""
from grading import lab2
from grading.checker import run_checker
from grading.lab2 import observer, rules

if __name__ == '__main__':
    run_checker(lab2, rules, observer.observe)
