"""Backlash and lost motion of internal involute pairs (Li et al. 2012, "Backlash
control and compensation for internal meshing involute spur gears"), per
mesh and carried to the output of a whole train.

Per mesh (a ``backlash:`` block on a mesh link, see :mod:`powergraph.model.block_backlash`):
equivalent profile shift from over-pin M values (Eqs. 12-14), the no-backlash working
pressure angle and centre distance (Eqs. 15-16) in two variants -- ``paper`` (Eq. 15 as
printed, without tan α) and ``standard`` (``inv α′ = inv α + 2 tan α (x1 − x2)/(z1 − z2)``)
-- the eccentric offset a″ (Eq. 9), and the lost-motion terms in arc-minutes via Eq. (1).
The centre-distance variation over the eccentric's turns (Eqs. 4-6) is
:func:`centre_distance_curve`.

Train level: :func:`analyse_backlash` refers each mesh's play to the output with the
inputs held, through the kinematic sensitivities, and sums worst case and root-sum-square.

Examples
--------
>>> from powergraph.model import load_model
>>> report = analyse_backlash(load_model("models/backlash_li2012.yaml"))   # doctest: +SKIP
>>> [round(m.pair.eccentric_offset["paper"], 3) for m in report.meshes]    # doctest: +SKIP
[2.578, 2.561]
"""
from __future__ import annotations

from powergraph.analyses.backlash.centre_distance import (
    CentreDistanceCurve,
    centre_distance,
    centre_distance_curve,
    period_turns,
)
from powergraph.analyses.backlash.format import format_arcmin
from powergraph.analyses.backlash.involute import (
    VARIANTS,
    involute,
    inverse_involute,
    no_backlash_centre_distance,
    over_pin_distance,
    pin_pressure_angle,
    shift_coefficient,
    standard_centre_distance,
    working_pressure_angle,
)
from powergraph.analyses.backlash.pair import (
    ARCMIN_PER_RAD,
    LOST_MOTION_TERMS,
    PairBacklash,
    analyse_pair,
    eccentric_offset,
    eccentricity_backlash,
    lost_motion_arcmin,
    thickness_backlash,
)
from powergraph.analyses.backlash.train import (
    BacklashReport,
    MeshBacklash,
    analyse_backlash,
    mesh_backlash,
)

__all__ = [
    "ARCMIN_PER_RAD", "LOST_MOTION_TERMS", "VARIANTS", "BacklashReport",
    "CentreDistanceCurve", "MeshBacklash", "PairBacklash", "analyse_backlash",
    "analyse_pair", "centre_distance", "centre_distance_curve", "eccentric_offset",
    "eccentricity_backlash", "format_arcmin", "involute", "inverse_involute",
    "lost_motion_arcmin", "mesh_backlash", "no_backlash_centre_distance",
    "over_pin_distance", "period_turns", "pin_pressure_angle", "shift_coefficient",
    "standard_centre_distance", "thickness_backlash", "working_pressure_angle",
]
