// pluginlib_compat: the ROS 1 header name <pluginlib/class_list_macros.h> for Debian 12's
// pluginlib 5.2, which ships only <pluginlib/class_list_macros.hpp> (PLUGINLIB_EXPORT_CLASS).
#ifndef PLUGINLIB__CLASS_LIST_MACROS_H_
#define PLUGINLIB__CLASS_LIST_MACROS_H_

#include <pluginlib/class_list_macros.hpp>

#endif  // PLUGINLIB__CLASS_LIST_MACROS_H_
