"""ownctl.experiment."""
