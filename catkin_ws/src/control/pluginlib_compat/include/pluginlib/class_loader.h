// pluginlib_compat: the ROS 1 header name <pluginlib/class_loader.h> for Debian 12's pluginlib 5.2,
// which ships only <pluginlib/class_loader.hpp> (pluginlib::ClassLoader<T>).
#ifndef PLUGINLIB__CLASS_LOADER_H_
#define PLUGINLIB__CLASS_LOADER_H_

#include <pluginlib/class_loader.hpp>

#endif  // PLUGINLIB__CLASS_LOADER_H_
