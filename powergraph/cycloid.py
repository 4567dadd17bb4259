"""``powergraph.cycloid``: cycloid transmission fluctuation (seeds/003, Csobán 2021).

A thin alias of :mod:`powergraph.analyses.cycloid`, where the code and documentation live.

Examples
--------
>>> from powergraph.cycloid import cycloid_fluctuation
>>> r = cycloid_fluctuation(module=1, teeth=9, profile_error=0.0)
>>> abs(float(r.ratio.max()) - 9.0) < 1e-9
True
"""
from powergraph.analyses.cycloid import *  # noqa: F401,F403  (the public API, re-exported)
from powergraph.analyses.cycloid import __all__  # noqa: F401
