"""``powergraph.backlash``: backlash and lost motion (seeds/002, Li et al. 2012).

A thin re-export of :mod:`powergraph.analyses.backlash`; see there.

Examples
--------
>>> from powergraph.backlash import analyse_backlash, format_arcmin
>>> format_arcmin(2.0583)
'2\\'3.5"'
"""
from __future__ import annotations

from powergraph.analyses.backlash import *  # noqa: F401,F403
from powergraph.analyses.backlash import __all__  # noqa: F401
