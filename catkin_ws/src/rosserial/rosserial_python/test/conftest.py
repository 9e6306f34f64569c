"""Puts this folder on sys.path, so that its tests import the helper modules next to them
(fake_device); pytest runs with --import-mode=importlib (pytest.ini), which does not."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
