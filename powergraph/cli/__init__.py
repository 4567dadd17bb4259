"""Command line (README "Commands", docs/architecture.md). Each command lives in its own ``cmd_*.py`` module."""
