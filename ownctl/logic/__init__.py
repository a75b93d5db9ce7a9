"""ownctl.logic."""
