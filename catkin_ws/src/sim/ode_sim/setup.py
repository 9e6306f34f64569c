from setuptools import setup
from catkin_pkg.python_setup import generate_distutils_setup

setup(**generate_distutils_setup(packages=['ode_sim', 'ode_sim.description', 'ode_sim.engine', 'ode_sim.ros',
                                           'ode_sim.ros.plugins'], package_dir={'': 'src'}))
