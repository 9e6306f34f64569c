"""rqt_plot re-implementation: live plots of numeric fields of ROS messages (PyQt5 + pyqtgraph)."""
