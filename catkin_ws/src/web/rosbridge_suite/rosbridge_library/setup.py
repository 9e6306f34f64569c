from setuptools import setup
from catkin_pkg.python_setup import generate_distutils_setup

setup(**generate_distutils_setup(
    packages=['rosbridge_library', 'rosbridge_library.internal', 'rosbridge_library.capabilities'],
    package_dir={'': 'src'}))
