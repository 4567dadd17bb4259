"""Volume of RV-reducer parts and whole trains, Pan & Wang (2019),
"Volume calculation of RV reducer".

* :func:`volume` / :func:`model_volume` — every component with a ``geometry`` block, by the
  paper's Eqs. (1)–(7), times ``count``, and the total, Eq. (8).
* :mod:`~powergraph.analyses.volume.formulas` — the equations as plain functions, with the
  reading of the OCR-damaged Eqs. (3)–(5).
* :mod:`~powergraph.analyses.volume.involute` — the exact rack-generated gear outline, and the
  error of the paper's pitch-circle cylinder (:func:`pitch_circle_errors`).
* :mod:`~powergraph.analyses.volume.cycloid_profile` — the exact cycloid disc outline.
* power density = output power / total volume, in kW/L (:func:`power_density`).

Examples
--------
>>> from powergraph.analyses.volume import gear_volume
>>> round(gear_volume(1.0, 20, 10.0, 0.0) / 3.141592653589793, 9)
1000.0
"""
from powergraph.analyses.volume.analysis import component_volume, model_volume, volume
from powergraph.analyses.volume.cycloid_profile import cycloid_disc_area, cycloid_disc_outline
from powergraph.analyses.volume.formulas import (
    crankshaft_volume,
    cycloid_disc_volume,
    gear_volume,
    needle_gear_volume,
    planet_frame_1_volume,
    planet_frame_2_volume,
)
from powergraph.analyses.volume.involute import (
    STANDARD_RACK,
    BasicRack,
    ProfileErrorTable,
    gear_outline,
    pitch_circle_area,
    pitch_circle_error,
    pitch_circle_errors,
    profile_area,
    space_half_angle,
)
from powergraph.analyses.volume.polygon import shoelace_area
from powergraph.analyses.volume.result import (
    POWER_DENSITY_UNIT,
    ComponentVolume,
    VolumeResult,
    power_density,
)

__all__ = [
    "volume", "model_volume", "component_volume", "VolumeResult", "ComponentVolume",
    "power_density", "POWER_DENSITY_UNIT",
    "gear_volume", "cycloid_disc_volume", "needle_gear_volume", "crankshaft_volume",
    "planet_frame_1_volume", "planet_frame_2_volume",
    "BasicRack", "STANDARD_RACK", "gear_outline", "profile_area", "space_half_angle",
    "pitch_circle_area", "pitch_circle_error", "pitch_circle_errors", "ProfileErrorTable",
    "cycloid_disc_outline", "cycloid_disc_area", "shoelace_area",
]
