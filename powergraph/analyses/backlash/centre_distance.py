"""Centre distance of an internal pair over the eccentric's turns, Eqs. (4)-(6) and Fig. 3
of Li et al. (2012).

A is the internal gear's base-circle centre, B the external gear's; O1, O2 the eccentric
shaft's two axes. |AO1| = F_r1/2 and |BO2| = F_r2/2 (the gears' eccentricities, Eq. 7's
Δe = F_r/2), |O1O2| the eccentric offset. When the eccentric turns by θ the external gear
turns by (Z1 − Z2)θ/Z2 about O2, and Eq. (4) as printed gives

    |AB|² = (|O1O2| cos θ + |BO2| cos[(Z1−Z2)θ/Z2 + β] + |AO1|)²
          + (|O1O2| sin θ + |BO2| sin[(Z1−Z2)θ/Z2 + β])².

(The text says the external gear turns *against* the eccentric; that is Eq. (4) with
θ → −θ and β → −β, the same curve mirrored, with the same extremes and period.)
Eqs. (5)-(6): |AB|max = |AO1| + |O1O2| + |BO2|, |AB|min = |O1O2| − (|AO1| + |BO2|), reached
only for some β. The curve repeats every Z2/gcd(Z1 − Z2, Z2) turns of the eccentric;
the paper's "T = Z2/(Z1 − Z2) = 20 r" for Z1 = 45, Z2 = 40 is 8 by its own formula.
"""
from __future__ import annotations

import math

import numpy as np

from powergraph.records import record


@record
class CentreDistanceCurve:
    """|AB| (mm) against the eccentric's angle, in turns; Eq. (5)/(6) bounds."""

    turns: tuple[float, ...]
    distance: tuple[float, ...]
    offset: float
    eccentricity_internal: float
    eccentricity_external: float
    z_internal: int
    z_external: int
    beta: float
    period_turns: int
    maximum: float
    minimum: float

    def text_report(self) -> str:
        """The sampled range and the Eq. (5)/(6) bounds."""
        from powergraph.analyses.backlash.report import curve_text

        return curve_text(self)

    def plot(self, ax=None, **kwargs):
        """|AB| over the turns (delegates, lazily, to
        :func:`powergraph.plot.backlash.plot_centre_distance`)."""
        from powergraph.plot.backlash import plot_centre_distance

        return plot_centre_distance(self, ax=ax, **kwargs)

    def to_dict(self) -> dict:
        """``{turns, distance (mm), offset, period_turns, maximum_eq5, minimum_eq6,
        eccentricity, beta}``."""
        return {"turns": list(self.turns), "distance": list(self.distance),
                "offset": self.offset, "period_turns": self.period_turns,
                "maximum_eq5": self.maximum, "minimum_eq6": self.minimum,
                "eccentricity": {"internal": self.eccentricity_internal,
                                 "external": self.eccentricity_external},
                "beta": self.beta}


def period_turns(z_internal: int, z_external: int) -> int:
    """Turns of the eccentric after which |AB| repeats: Z2/gcd(Z1 − Z2, Z2).

    >>> period_turns(45, 40)
    8
    """
    return z_external // math.gcd(z_internal - z_external, z_external)


def centre_distance(theta: np.ndarray | float, offset: float, eccentricity_internal: float,
                    eccentricity_external: float, z_internal: int, z_external: int,
                    beta: float = 0.0) -> np.ndarray:
    """|AB| of Eq. (4) at eccentric angle(s) θ (radians).

    >>> round(float(centre_distance(0.0, 2.5, 0.0125, 0.009, 45, 40)), 4)   # Eq. (5)
    2.5215
    """
    theta = np.asarray(theta, dtype=float)
    spin = (z_internal - z_external) * theta / z_external + beta
    x = offset * np.cos(theta) + eccentricity_external * np.cos(spin) + eccentricity_internal
    y = offset * np.sin(theta) + eccentricity_external * np.sin(spin)
    return np.hypot(x, y)


def centre_distance_curve(offset: float, runout_internal: float, runout_external: float,
                          z_internal: int, z_external: int, beta: float = 0.0,
                          turns: float | None = None,
                          points_per_turn: int = 360) -> CentreDistanceCurve:
    """Fig. 3: the centre distance over ``turns`` turns (default: one period).

    Parameters
    ----------
    offset : float
        Eccentric offset |O1O2| (mm).
    runout_internal, runout_external : float
        Radial runouts F_r1, F_r2 (mm); the eccentricities are half of them.
    z_internal, z_external : int
        Tooth counts Z1 (internal), Z2 (external).
    beta : float
        Initial phase β of the external gear's eccentricity (radians).
    turns : float, optional
        How many turns of the eccentric to sample; default one period.
    points_per_turn : int
        Samples per turn.

    Examples
    --------
    >>> c = centre_distance_curve(2.5, 0.025, 0.018, 45, 40)
    >>> c.period_turns, round(c.maximum, 4), round(c.minimum, 4)
    (8, 2.5215, 2.4785)
    """
    period = period_turns(z_internal, z_external)
    span = float(period if turns is None else turns)
    count = max(2, int(round(span * points_per_turn)) + 1)
    grid = np.linspace(0.0, span, count)
    e1, e2 = runout_internal / 2.0, runout_external / 2.0
    values = centre_distance(2.0 * math.pi * grid, offset, e1, e2, z_internal, z_external,
                             beta)
    return CentreDistanceCurve(turns=tuple(grid.tolist()), distance=tuple(values.tolist()),
                               offset=offset, eccentricity_internal=e1,
                               eccentricity_external=e2, z_internal=z_internal,
                               z_external=z_external, beta=beta, period_turns=period,
                               maximum=offset + e1 + e2, minimum=offset - (e1 + e2))
