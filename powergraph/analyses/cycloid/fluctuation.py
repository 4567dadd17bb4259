"""Transmission fluctuation of one cycloid stage with a profile error (Csobán 2021)."""
from __future__ import annotations

import math
from typing import Any

import numpy as np

from powergraph.analyses.cycloid.contact import contact_curve, handovers
from powergraph.analyses.cycloid.geometry import CycloidGeometry, cycloid_geometry
from powergraph.analyses.cycloid.report import stage_text
from powergraph.errors import UsageError
from powergraph.display import Displayed
from powergraph.records import record

#: Samples of the crank angle per contact segment (a segment is 2π/z2 of crank angle).
POINTS_PER_SEGMENT = 32
#: The paper's step of the crank angle for its central differences (Eq. 10), degrees.
PAPER_STEP_DEG = 2.0


@record(eq=False, repr=False)
class CycloidFluctuation(Displayed):
    """Ratio of a cycloid stage over one input (crank) revolution.

    Attributes
    ----------
    geometry : CycloidGeometry
    profile_error : float
        ``d`` (mm).
    crank_angle : ndarray
        Sampled crank angles ``θ`` over one revolution (rad).
    output_angle : ndarray
        Disc rotation ``ψ = −θ/z1 + δ`` (rad; the disc turns against the crank).
    ratio : ndarray
        Exact instantaneous ratio ``i = −dθ/dψ`` at each sample.
    contact_pin : ndarray of int
        The pin in contact (pin ``k`` at angle ``2πk/z2``).
    handover_angle : ndarray
        Crank angles where the contact passes to the next pin (rad).
    ratio_before, ratio_after : ndarray
        The one-sided ratios at each hand-over (outgoing pin, incoming pin).
    max_deviation_percent : float
        Exact maximum of ``|Δi| = |i_ideal − i|/i_ideal·100`` over the revolution.
    max_deviation_angle : float
        Crank angle (rad) where it occurs (a hand-over: one-sided limit).
    paper_crank_angle, paper_ratio : ndarray
        The paper's ratio (Eq. 10): central differences of ``ψ`` on a 2° grid from ``θ = 0``.
    """

    geometry: CycloidGeometry
    profile_error: float
    crank_angle: np.ndarray
    output_angle: np.ndarray
    ratio: np.ndarray
    contact_pin: np.ndarray
    handover_angle: np.ndarray
    ratio_before: np.ndarray
    ratio_after: np.ndarray
    max_deviation_percent: float
    max_deviation_angle: float
    paper_crank_angle: np.ndarray
    paper_ratio: np.ndarray

    def _summary(self) -> str:
        return (f"z1 = {self.geometry.teeth}, d = {self.profile_error:g} mm: max |Δi| "
                f"{self.max_deviation_percent:.4g} %")

    def _records(self) -> list[dict[str, Any]]:
        """One row per sampled crank angle (deg): the exact ratio and the pin in contact."""
        return [{"crank_angle_deg": float(np.degrees(a)), "ratio": float(r), "pin": int(p)}
                for a, r, p in zip(self.crank_angle, self.ratio, self.contact_pin)]


    @property
    def max_deviation_percent_2deg(self) -> float:
        """The paper's maximum: largest ``|Δi|`` of its 2° central differences."""
        return float(np.max(np.abs(deviation_percent(self.paper_ratio, self.ratio_nominal))))

    @property
    def ratio_nominal(self) -> float:
        """The ideal ratio ``z1``."""
        return float(self.geometry.teeth)

    @property
    def deviation_percent(self) -> np.ndarray:
        """``Δi = (i_ideal − i)/i_ideal·100`` at each sample (paper Eq. 11)."""
        return deviation_percent(self.ratio, self.ratio_nominal)

    @property
    def segments(self) -> int:
        """Contact segments per input revolution (``z2`` when the error is not zero)."""
        return int(self.handover_angle.size)

    @property
    def large_teeth_limit_percent(self) -> float:
        """``100π·d/(e·z2)``: the maximum deviation as ``z1 → ∞``
        (tests/data/published_values.yaml)."""
        g = self.geometry
        return 100.0 * math.pi * self.profile_error / (g.eccentricity * g.pins)

    def contact_segments(self) -> list[tuple[int, np.ndarray, np.ndarray]]:
        """``(pin, crank angles, ratios)`` of each contact segment, ends at the hand-overs.

        The ends carry the exact one-sided ratios; the last segment runs past ``2π``.
        Without error the whole revolution is one segment.
        """
        theta, ratio = self.crank_angle, self.ratio
        if self.segments == 0:
            return [(int(self.contact_pin[0]), theta, ratio)]
        start = self.handover_angle
        stop = np.append(start[1:], start[0] + 2.0 * np.pi)
        unwrapped = np.where(theta < start[0], theta + 2.0 * np.pi, theta)
        segments = []
        for j, (lo, hi) in enumerate(zip(start, stop)):
            inside = np.nonzero((unwrapped > lo) & (unwrapped < hi))[0]
            inside = inside[np.argsort(unwrapped[inside])]
            after, before = self.ratio_after[j], self.ratio_before[(j + 1) % self.segments]
            segments.append((int(self.contact_pin[inside[0]]) if inside.size else -1,
                             np.concatenate([[lo], unwrapped[inside], [hi]]),
                             np.concatenate([[after], ratio[inside], [before]])))
        return segments

    def deviation_segments(self) -> list[tuple[int, np.ndarray, np.ndarray]]:
        """``(pin, crank angles, Δi in %)`` of each contact segment (paper Eq. 11).

        Returns
        -------
        list of tuple
            :meth:`contact_segments` with each ratio as its deviation
            :func:`deviation_percent` from ``ratio_nominal``.
        """
        return [(pin, angle, deviation_percent(ratio, self.ratio_nominal))
                for pin, angle, ratio in self.contact_segments()]

    def text_report(self) -> str:
        """The readable report (what the command line prints)."""
        return stage_text(self)

    def plot(self, ax=None, **kwargs):
        """Ratio against crank angle (delegates, lazily, to
        :func:`powergraph.plot.cycloid.plot_ratio_fluctuation`)."""
        from powergraph.plot.cycloid import plot_ratio_fluctuation

        return plot_ratio_fluctuation(self, ax=ax, **kwargs)

    def to_dict(self) -> dict:
        """Plain data for ``--json``."""
        return {
            **self.geometry.to_dict(),
            "profile_error": self.profile_error,
            "ratio_nominal": self.ratio_nominal,
            "max_deviation_percent": self.max_deviation_percent,
            "max_deviation_angle_deg": math.degrees(self.max_deviation_angle),
            "max_deviation_percent_2deg": self.max_deviation_percent_2deg,
            "large_teeth_limit_percent": self.large_teeth_limit_percent,
            "segments": self.segments,
            "handover_angle_deg": np.degrees(self.handover_angle).tolist(),
            "handover_ratio_before": self.ratio_before.tolist(),
            "handover_ratio_after": self.ratio_after.tolist(),
            "crank_angle_deg": np.degrees(self.crank_angle).tolist(),
            "output_angle_deg": np.degrees(self.output_angle).tolist(),
            "ratio": self.ratio.tolist(),
            "deviation_percent": self.deviation_percent.tolist(),
            "contact_pin": self.contact_pin.tolist(),
            "crank_angle_deg_2deg": np.degrees(self.paper_crank_angle).tolist(),
            "ratio_2deg": self.paper_ratio.tolist(),
        }


def deviation_percent(ratio, nominal: float):
    """Paper Eq. (11): ``(i_ideal − i_real)/i_ideal·100``.

    >>> round(float(deviation_percent(8.91, 9.0)), 12)
    1.0
    """
    return (nominal - np.asarray(ratio)) / nominal * 100.0


def cycloid_fluctuation(module: float, teeth: int, profile_error: float, shift: float = 0.3,
                        rc: float = 1.0,
                        points_per_segment: int = POINTS_PER_SEGMENT) -> CycloidFluctuation:
    """Ratio fluctuation of a cycloid stage whose profile is off by ``d`` along its normal.

    Parameters
    ----------
    module : float
        Module ``m`` (mm).
    teeth : int
        Disc teeth ``z1`` (pins ``z2 = z1 + 1``).
    profile_error : float
        ``d`` (mm), the profile moved inward along its normal.
    shift, rc : float
        Profile-shift coefficient ``x`` and pin-radius factor ``rc*`` (paper: 0.3 and 1).
    points_per_segment : int
        Crank-angle samples per contact segment for the curve (the maximum does not
        depend on it: hand-overs are located exactly).

    Returns
    -------
    CycloidFluctuation

    Examples
    --------
    Table 2 of the paper (m = 1, z1 = 9, x = 0.3, rc* = 1, d = 0.1 mm):

    >>> r = cycloid_fluctuation(1, 9, 0.1)
    >>> r.ratio_nominal, r.segments
    (9.0, 10)
    >>> r.max_deviation_percent > r.max_deviation_percent_2deg
    True
    """
    geometry = cycloid_geometry(module, teeth, shift, rc, profile_error)
    if isinstance(points_per_segment, bool) or not isinstance(points_per_segment, int) \
            or points_per_segment < 4:
        raise UsageError(f"points_per_segment must be an integer >= 4, "
                         f"got {points_per_segment!r}")
    d = float(profile_error)
    theta = np.arange(geometry.pins * points_per_segment) * (
        2.0 * np.pi / (geometry.pins * points_per_segment))
    pin, delta, rate = contact_curve(geometry, d, theta)
    ratio = -1.0 / rate
    if d > 0:
        angle, rate_before, rate_after = handovers(geometry, d, theta, pin)
    else:  # without error the driving pins share the contact: no hand-overs
        angle = rate_before = rate_after = np.empty(0)
    order = np.argsort(angle)
    angle, before, after = angle[order], -1.0 / rate_before[order], -1.0 / rate_after[order]
    peak, peak_angle = _exact_peak(theta, ratio, angle, before, after, float(geometry.teeth))
    paper_theta, paper_ratio = central_difference_ratio(geometry, d)
    arrays = (theta, delta - theta / geometry.teeth, ratio, pin, angle, before, after)
    return CycloidFluctuation(geometry, d, *map(read_only, arrays), max_deviation_percent=peak,
                              max_deviation_angle=peak_angle,
                              paper_crank_angle=read_only(paper_theta),
                              paper_ratio=read_only(paper_ratio))


def _exact_peak(theta, ratio, angle, before, after, nominal) -> tuple[float, float]:
    """Largest |Δi| and its crank angle, over the samples and both sides of the hand-overs.

    Between hand-overs |Δi| is monotonic (checked for 0.05 ≤ x ≤ 0.9, 3 ≤ z1 ≤ 117), so the
    maximum is a one-sided value at a hand-over; the samples only matter without error.
    """
    values = np.abs(deviation_percent(np.concatenate([ratio, before, after]), nominal))
    angles = np.concatenate([theta, angle, angle])
    k = int(np.argmax(values))
    return float(values[k]), float(angles[k])


def central_difference_ratio(geometry: CycloidGeometry, profile_error: float,
                             step_deg: float = PAPER_STEP_DEG):
    """The paper's ratio (Eq. 10): central differences of ``ψ`` on a grid of crank angles.

    ``i_n = (θ_{n+1} − θ_{n−1}) / (ψ_{n−1} − ψ_{n+1})`` on ``θ_n = n·step`` from 0; ``ψ`` is
    extended over the revolution by ``ψ(θ + 2π) = ψ(θ) − 2π/z1``.

    Returns
    -------
    crank_angle, ratio : ndarray

    Examples
    --------
    >>> from powergraph.analyses.cycloid.geometry import cycloid_geometry
    >>> _, ratio = central_difference_ratio(cycloid_geometry(1, 9), 0.0)
    >>> bool(np.allclose(ratio, 9.0))
    True
    """
    count = int(round(360.0 / step_deg))
    if count < 3 or not math.isclose(count * step_deg, 360.0):
        raise UsageError(f"the step must divide 360°, got {step_deg}")
    theta = np.arange(count) * math.radians(step_deg)
    _, delta, _ = contact_curve(geometry, profile_error, theta)
    psi = delta - theta / geometry.teeth
    turn = 2.0 * np.pi / geometry.teeth
    ahead = np.append(psi[1:], psi[0] - turn)
    behind = np.insert(psi[:-1], 0, psi[-1] + turn)
    return theta, 2.0 * math.radians(step_deg) / (behind - ahead)


def read_only(values) -> np.ndarray:
    """A read-only copy of an array (results are immutable)."""
    array = np.array(values)
    array.flags.writeable = False
    return array
