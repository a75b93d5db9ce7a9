"""Scenario tests use the CLI tests' store fixtures."""

from tests.cli.conftest import _empty_store, ownctl

__all__ = ["_empty_store", "ownctl"]
