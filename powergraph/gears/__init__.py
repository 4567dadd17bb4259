"""Gear geometry and mesh physics that several layers need (base layer: imports only
:mod:`powergraph.errors`): the involute function, contact ratios, Ohlendorf's loss factor
and the ISO/TR 14179-2 friction coefficient."""
