"""One internal involute pair (Li et al. 2012): equivalent shift, eccentric offset a″ and
lost motion, Eqs. (1)-(3), (7)-(9), (12)-(16).

Readings of the paper (see also the package docstring):

- Eq. (1) divides the circumferential backlash j_t by the *internal* gear's pitch radius
  m·Z1/2, so its arc-minutes are the internal gear's rotation with the external gear held
  (both axes held on the eccentric).
- The equivalent shift is taken from the M values the paper prescribes (the internal gear's
  smallest, the external gear's largest) *relative to the standard M*: x = x(M) − x(M_std),
  so that a gear measuring exactly its standard M has no shift.
- Thickness term, Eq. (2): j_t = (E_M,int − E_M,ext)·tan α with E_M = M − M_std of the same
  M values. Runout, Eqs. (3), (7): j_t = 2 tan α Σ F_r/2 (worst phase, sin φ = 1); bearing
  clearance likewise with Δe = u_r/2.
- ``before`` = thickness + runout + bearing at the standard centre distance (Eq. 8 with all
  of Eq. 7's terms). ``after`` = what Eq. (9) cannot remove: a″ takes up the thickness term
  (through a′) and the bearing term (Σu_r/2), the runout term is left.
"""
from __future__ import annotations

import math
from dataclasses import field
from types import MappingProxyType
from typing import Mapping

from powergraph.analyses.backlash.involute import (
    VARIANTS,
    no_backlash_centre_distance,
    shift_coefficient,
    standard_centre_distance,
    working_pressure_angle,
)
from powergraph.records import record

#: Arc-minutes per radian (Eq. 1 is j_t / r in radians, times this).
ARCMIN_PER_RAD = 180.0 * 60.0 / math.pi
LOST_MOTION_TERMS = ("thickness", "runout", "bearing", "before", "after")


def lost_motion_arcmin(backlash_mm: float, module: float, teeth: int) -> float:
    """Eq. (1): circumferential backlash j_t (mm) → rotation (arcmin) of a gear of z teeth.

    ``j_φ = 180·60/(1000π) · j_t[µm] / (m z / 2)``; the paper's 6.876 is 2·180·60/(1000π).

    >>> round(lost_motion_arcmin(0.028025, 1.0, 45), 4)
    4.2819
    """
    return backlash_mm / (module * teeth / 2.0) * ARCMIN_PER_RAD


def thickness_backlash(deviation_internal: float, deviation_external: float,
                       alpha: float) -> float:
    """Eq. (2): j_t = E_M tan α, with E_M = E_M,int − E_M,ext (both thin the teeth).

    >>> round(thickness_backlash(0.045, -0.032, math.radians(20)), 6)
    0.028026
    """
    return (deviation_internal - deviation_external) * math.tan(alpha)


def eccentricity_backlash(eccentricities: tuple[float, ...], alpha: float) -> float:
    """Eqs. (3), (7) at the worst phase: j_t = 2 tan α Σ Δe_i.

    >>> round(eccentricity_backlash((0.011, 0.0075), math.radians(20)), 6)
    0.013467
    """
    return 2.0 * math.tan(alpha) * sum(eccentricities)


def eccentric_offset(no_backlash_distance: float, runout: tuple[float, ...],
                     bearing_clearance: tuple[float, ...]) -> float:
    """Eq. (9): a″ = a′ − (F_r1 + F_r2)/2 + Σ u_r/2.

    >>> round(eccentric_offset(2.5353, (0.022, 0.015), (0.005, 0.006)), 4)
    2.5223
    """
    return no_backlash_distance - sum(runout) / 2.0 + sum(bearing_clearance) / 2.0


@record
class PairBacklash:
    """Backlash of one internal pair. Lengths in mm, angles in degrees, lost motion in
    arc-minutes of the internal gear (Eq. 1). Per-gear mappings are keyed by gear id;
    per-variant mappings by ``"paper"`` / ``"standard"`` (Eq. 15 without / with tan α).
    """

    internal: str
    external: str
    teeth: Mapping[str, int]
    module: float
    pressure_angle: float
    m_used: Mapping[str, float]
    m_deviation: Mapping[str, float]
    shift_coefficient: Mapping[str, float]
    standard_centre_distance: float
    working_pressure_angle: Mapping[str, float]
    no_backlash_centre_distance: Mapping[str, float]
    eccentric_offset: Mapping[str, float]
    backlash_mm: Mapping[str, float]
    lost_motion_arcmin: Mapping[str, float]
    runout: Mapping[str, float] = field(default_factory=dict)
    assembly: str = "standard"

    @property
    def equivalent_shift(self) -> Mapping[str, float]:
        """x·m of each gear (mm)."""
        return MappingProxyType({g: x * self.module for g, x in self.shift_coefficient.items()})

    @property
    def assembled_lost_motion(self) -> float:
        """Lost motion (arcmin, internal gear) of the pair as assembled: before or after."""
        key = "after" if self.assembly == "compensated" else "before"
        return self.lost_motion_arcmin[key]

    def text_report(self) -> str:
        """The readable report of the pair (gear ids as given)."""
        from powergraph.analyses.backlash.report import pair_text

        return pair_text(self)

    def plot(self, ax=None, **kwargs):
        """Lost-motion terms before and after compensation (delegates, lazily, to
        :func:`powergraph.plot.backlash.plot_lost_motion`)."""
        from powergraph.plot.backlash import plot_lost_motion

        return plot_lost_motion({f"{self.internal}-{self.external}": self}, ax=ax, **kwargs)

    def to_dict(self) -> dict:
        """Every quantity; per-gear values keyed by gear id, per-variant ones by
        ``"paper"`` / ``"standard"``; lengths in mm, lost motion in arcmin."""
        return {"internal": self.internal, "external": self.external,
                "equivalent_shift": dict(self.equivalent_shift),
                "shift_coefficient": dict(self.shift_coefficient),
                "M_used": dict(self.m_used), "M_deviation": dict(self.m_deviation),
                "standard_centre_distance": self.standard_centre_distance,
                "working_pressure_angle_deg": dict(self.working_pressure_angle),
                "no_backlash_centre_distance": dict(self.no_backlash_centre_distance),
                "eccentric_offset": dict(self.eccentric_offset),
                "circumferential_backlash_mm": dict(self.backlash_mm),
                "lost_motion_arcmin": dict(self.lost_motion_arcmin),
                "assembly": self.assembly}


def analyse_pair(block, z_internal: int, z_external: int) -> PairBacklash:
    """Equivalent shift, a′, a″ and lost-motion terms of one internal pair.

    Parameters
    ----------
    block : BacklashBlock
        A validated ``backlash:`` block (:mod:`powergraph.model.block_backlash`).
    z_internal, z_external : int
        Tooth counts of the internal and external gear.

    Returns
    -------
    PairBacklash

    Examples
    --------
    >>> from powergraph.model.block_backlash import BacklashBlock
    >>> block = BacklashBlock(module=1, pin_diameter=1.732, internal="ring", external="pinion",
    ...     standard_M={"ring": 42.434, "pinion": 42.436},
    ...     measured_M={"ring": [42.485, 42.479], "pinion": [42.401, 42.404]},
    ...     runout={"ring": 0.022, "pinion": 0.015}, bearing_clearance=[0.005, 0.006])
    >>> pair = analyse_pair(block, 45, 40)
    >>> round(pair.eccentric_offset["paper"], 3), round(pair.eccentric_offset["standard"], 3)
    (2.578, 2.522)
    >>> round(pair.lost_motion_arcmin["after"], 3)      # 2'3.5"
    2.058
    """
    alpha = math.radians(block.pressure_angle)
    gears = {block.internal: (z_internal, True), block.external: (z_external, False)}
    used = {block.internal: min(block.measured_M[block.internal]),
            block.external: max(block.measured_M[block.external])}
    deviation = {g: used[g] - block.standard_M[g] for g in gears}
    shift = {g: _relative_shift(used[g], block.standard_M[g], z, internal, block, alpha)
             for g, (z, internal) in gears.items()}
    a = standard_centre_distance(block.module, z_internal, z_external)
    angles = {v: working_pressure_angle(shift[block.internal], shift[block.external],
                                        z_internal, z_external, alpha, v) for v in VARIANTS}
    a_prime = {v: no_backlash_centre_distance(a, alpha, angles[v]) for v in VARIANTS}
    runout = (block.runout.get(block.internal, 0.0), block.runout.get(block.external, 0.0))
    offsets = {v: eccentric_offset(a_prime[v], runout, block.bearing_clearance)
               for v in VARIANTS}
    backlash = _backlash_terms(deviation[block.internal], deviation[block.external], runout,
                               block.bearing_clearance, alpha)
    return PairBacklash(
        internal=block.internal, external=block.external,
        teeth=_frozen({g: z for g, (z, _) in gears.items()}), module=block.module,
        pressure_angle=block.pressure_angle, m_used=_frozen(used),
        m_deviation=_frozen(deviation), shift_coefficient=_frozen(shift),
        standard_centre_distance=a,
        working_pressure_angle=_frozen({v: math.degrees(t) for v, t in angles.items()}),
        no_backlash_centre_distance=_frozen(a_prime), eccentric_offset=_frozen(offsets),
        backlash_mm=_frozen(backlash),
        lost_motion_arcmin=_frozen({k: lost_motion_arcmin(v, block.module, z_internal)
                                    for k, v in backlash.items()}),
        runout=_frozen(dict(zip((block.internal, block.external), runout))),
        assembly=block.assembly)


def _relative_shift(m_value: float, m_standard: float, teeth: int, internal: bool,
                    block, alpha: float) -> float:
    """x(M) − x(M_std): the shift the measured thinning is equivalent to."""
    args = (teeth, block.module, alpha, block.pin_diameter, internal)
    return shift_coefficient(m_value, *args) - shift_coefficient(m_standard, *args)


def _backlash_terms(dev_internal: float, dev_external: float, runout: tuple[float, float],
                    bearings: tuple[float, ...], alpha: float) -> dict[str, float]:
    """Circumferential backlash j_t (mm) of each term, before and after compensation."""
    thickness = thickness_backlash(dev_internal, dev_external, alpha)
    run = eccentricity_backlash(tuple(f / 2.0 for f in runout), alpha)
    bearing = eccentricity_backlash(tuple(u / 2.0 for u in bearings), alpha)
    return {"thickness": thickness, "runout": run, "bearing": bearing,
            "before": thickness + run + bearing, "after": run}


def _frozen(mapping: dict) -> Mapping:
    return MappingProxyType(dict(mapping))
