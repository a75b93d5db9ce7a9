"""ownctl.learn."""
