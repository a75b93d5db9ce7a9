"""ownctl.language."""
