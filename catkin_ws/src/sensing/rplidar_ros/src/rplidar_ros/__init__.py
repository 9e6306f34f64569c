"""Re-implementation of rplidar_ros (rplidarNode) for the RPLIDAR A1, plus an emulated A1."""
