"""Plotting. Every function takes ``ax=None``, returns the axes, and computes nothing.

Importing this package imports matplotlib (with the non-interactive Agg backend unless
one was chosen), so the rest of powergraph imports it lazily.
"""
from __future__ import annotations

import matplotlib

if matplotlib.get_backend().lower() not in ("agg", "module://matplotlib_inline.backend_inline"):
    try:
        matplotlib.use("Agg")
    except Exception:  # pragma: no cover - a backend already in use stays
        pass
