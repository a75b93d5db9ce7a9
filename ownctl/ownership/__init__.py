"""ownctl.ownership."""
