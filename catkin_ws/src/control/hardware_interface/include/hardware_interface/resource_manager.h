// Re-implementation of ros_control's hardware_interface (Noetic 0.20 API) for Debian 12.
#pragma once
#include <hardware_interface/internal/resource_manager.h>
