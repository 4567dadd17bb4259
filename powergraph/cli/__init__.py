"""Command line (SPEC §2). Each command lives in its own ``cmd_*.py`` module."""
