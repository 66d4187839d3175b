"""tutgen: worked solutions for rigid-body and robot dynamics problems from a YAML spec."""

__version__ = "0.1.0"
