"""Volume and power density of gear trains (seeds/004): re-exports
:mod:`powergraph.analyses.volume`.

Examples
--------
>>> from powergraph.volume import power_density
>>> power_density(2270.0, 1.0e6)      # kW/L
2.27
"""
from powergraph.analyses.volume import *  # noqa: F401,F403
from powergraph.analyses.volume import __all__  # noqa: F401
