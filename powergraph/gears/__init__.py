"""Gear geometry and mesh physics that several layers need (base layer: imports only other
base-layer modules): the involute function, contact ratios, Ohlendorf's loss factor, the
ISO/TR 14179-2 friction coefficient, and the spin-loss laws: SKF's bearing frictional
moment (:mod:`powergraph.gears.skf_bearing`) and Changenet & Velex's churning torque
(:mod:`powergraph.gears.churning`), read into a model by :mod:`powergraph.model.block_spin`."""
