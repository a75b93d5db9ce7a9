"""ownctl.store."""
