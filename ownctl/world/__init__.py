"""ownctl.world."""
