"""ownctl: learn and obey ownership relations and norms (a robot's ownership conscience)."""

__version__ = "0.1.0"
