#!/usr/bin/env python3
"""Lab 1 node 3: sends a number, or computes the result if the variant says so."""
from my_robot_controller.numbers import main

if __name__ == '__main__':
    main(3)
