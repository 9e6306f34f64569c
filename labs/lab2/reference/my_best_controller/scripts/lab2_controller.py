#!/usr/bin/env python3
"""Lab 2 controller: turtle 1 (ns1_<ISU>) visits the points, turtle 2 (ns2_<ISU>) repeats it."""
from my_best_controller.node import main

if __name__ == '__main__':
    main()
