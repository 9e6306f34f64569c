#!/usr/bin/python3
"""rostest checker of lab 4: run lab4.launch headless, observe scene, robot, sensors,
controllers and motion (sim time), report."""
from grading import lab4
from grading.checker import run_checker
from grading.lab4 import observer, rules

if __name__ == '__main__':
    run_checker(lab4, rules, observer.observe)
