"""rosserial_python: the host side of rosserial (re-implementation)."""
