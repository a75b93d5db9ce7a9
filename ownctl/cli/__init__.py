"""ownctl.cli."""
