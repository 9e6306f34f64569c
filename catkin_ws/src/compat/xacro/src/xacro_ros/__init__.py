"""ROS 1 `xacro` on top of the PyPI xacro 2.1.1 module (module named xacro_ros so that it
never shadows the PyPI `xacro` module it wraps)."""
from xacro_ros.resolve import find_package, install, PackageNotFound
from xacro_ros.cli import XacroError, expand, expand_to_string, dependencies, main

__all__ = ['find_package', 'install', 'PackageNotFound', 'XacroError', 'expand',
           'expand_to_string', 'dependencies', 'main']
