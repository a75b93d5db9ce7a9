"""ownctl.app."""
