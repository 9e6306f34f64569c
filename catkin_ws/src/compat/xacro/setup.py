from setuptools import setup
from catkin_pkg.python_setup import generate_distutils_setup

# The module is `xacro_ros`, not `xacro`: a `xacro` package of ours would shadow the PyPI module.
setup(**generate_distutils_setup(packages=['xacro_ros'], package_dir={'': 'src'}))
