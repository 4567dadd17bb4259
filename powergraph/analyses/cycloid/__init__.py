"""Cycloid transmission fluctuation from a profile error (Csobán 2021).

Public API: :func:`cycloid_fluctuation` (one stage), :func:`fluctuation_study` (the paper's
grid and least-squares refit), :func:`iso_tolerance` / :func:`profile_error_for_grade`
(ISO 286), :func:`cycloid_geometry`, and :func:`train_fluctuation` (a stage's fluctuation
carried to the output of a train, through :mod:`powergraph.kinematics`).
"""
from __future__ import annotations

from powergraph.analyses.cycloid.fit import (PAPER_FITS, PAPER_TEETH, FluctuationStudy,
                                             fluctuation_study)
from powergraph.analyses.cycloid.fluctuation import (CycloidFluctuation,
                                                     central_difference_ratio,
                                                     cycloid_fluctuation, deviation_percent)
from powergraph.analyses.cycloid.geometry import (CycloidGeometry, cycloid_geometry,
                                                  smallest_convex_radius)
from powergraph.analyses.cycloid.train import (StageAtOutput, TrainFluctuation,
                                               train_fluctuation)
from powergraph.gears.iso286 import GRADES, iso_tolerance, profile_error_for_grade

__all__ = [
    "CycloidFluctuation", "CycloidGeometry", "FluctuationStudy", "GRADES", "PAPER_FITS",
    "PAPER_TEETH", "central_difference_ratio", "cycloid_fluctuation", "cycloid_geometry",
    "deviation_percent", "fluctuation_study", "iso_tolerance",
    "profile_error_for_grade", "smallest_convex_radius", "StageAtOutput", "TrainFluctuation",
    "train_fluctuation",
]
