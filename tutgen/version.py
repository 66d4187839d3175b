"""The version of tutgen (the program; each file format has its own version, see tutgen/schemas.py)."""

__version__ = "0.1.0"
