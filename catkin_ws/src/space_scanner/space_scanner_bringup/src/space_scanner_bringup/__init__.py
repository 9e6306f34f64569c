"""The space scanner's bringup: the main demo's measurements (metrics) and its orchestration (demo)."""
