"""Distributions of toleranced model values, and their validation.

A tolerance is written in one of four forms (lengths in mm, or strings with a length unit
where the value is a length):

===========================================================  ===============================
``{distribution: uniform, min: A, max: B}``                  uniform on [A, B], A < B
``{distribution: normal, mean: M, sd: S[, low: L][, high: H]}``  normal, optionally truncated
                                                             to [L, H]; S > 0
``{nominal: N, tolerance: T[, distribution: uniform]}``      N ± T: a normal with σ = T/3
                                                             truncated at N ± T (±3σ; parts
                                                             outside the tolerance are
                                                             rejected at inspection), or
                                                             uniform on [N − T, N + T]; T ≥ 0,
                                                             T = 0 is the nominal value alone
``{nominal: N, grade: IT6, size: D[, distribution: …]}``     N ± IT/2, IT the ISO 286-1
                                                             standard tolerance of grade
                                                             IT5…IT9 for the nominal size D
===========================================================  ===============================

Every distribution is sampled through its quantile function (``ppf``) from uniform numbers
in [0, 1), so Monte Carlo sampling and the Sobol sequence share one code path.

Examples
--------
>>> import numpy as np
>>> d = parse_distribution({"nominal": 2.0, "tolerance": 0.3}, "x", (0.0, None))
>>> d.kind, d.mean, round(d.sd, 12), d.low, d.high
('normal', 2.0, 0.1, 1.7, 2.3)
>>> d.ppf(np.array([0.5])).tolist()
[2.0]
"""
from __future__ import annotations

import math
import re
from typing import Any, Mapping

import numpy as np

from powergraph.errors import ModelError, UsageError
from powergraph.gears.iso286 import GRADES, iso_tolerance
from powergraph.model.units import parse_number
from powergraph.records import record

FORMS = ("{distribution: uniform, min, max}", "{distribution: normal, mean, sd[, low, high]}",
         "{nominal, tolerance}", "{nominal, grade, size}")
KINDS = ("uniform", "normal", "constant")


@record
class Distribution:
    """One toleranced value's distribution.

    Attributes
    ----------
    kind : str
        ``uniform``, ``normal`` (truncated to [low, high] when those are finite) or
        ``constant`` (a zero tolerance: the nominal value alone).
    low, high : float
        Support (``-inf``/``inf`` for an untruncated normal).
    mean, sd : float
        Of the underlying normal (``sd`` 0 for a constant); for a uniform the midpoint and
        the standard deviation (B − A)/√12.
    """

    kind: str
    low: float
    high: float
    mean: float
    sd: float

    @property
    def nominal(self) -> float:
        """The centre value (the mean of the untruncated normal, the midpoint otherwise)."""
        return self.mean

    def ppf(self, u: np.ndarray) -> np.ndarray:
        """Quantile function: values from uniform numbers ``u`` in [0, 1).

        >>> Distribution("uniform", 1.0, 3.0, 2.0, 0.0).ppf(np.array([0.0, 0.25])).tolist()
        [1.0, 1.5]
        """
        u = np.asarray(u, dtype=float)
        if self.kind == "constant":
            return np.full(u.shape, self.mean)
        if self.kind == "uniform":
            return self.low + (self.high - self.low) * u
        from scipy.special import ndtr, ndtri

        lo = ndtr((self.low - self.mean) / self.sd) if math.isfinite(self.low) else 0.0
        hi = ndtr((self.high - self.mean) / self.sd) if math.isfinite(self.high) else 1.0
        p = np.clip(lo + (hi - lo) * u, np.nextafter(0.0, 1.0), np.nextafter(1.0, 0.0))
        return np.clip(self.mean + self.sd * ndtri(p), self.low, self.high)

    def to_dict(self) -> dict:
        return {"kind": self.kind, "low": self.low, "high": self.high, "mean": self.mean,
                "sd": self.sd}


def parse_distribution(raw: Any, place: str, domain: tuple[float | None, float | None],
                       length: bool = False, open_low: bool = False) -> Distribution:
    """Validate one tolerance entry into a :class:`Distribution`.

    Parameters
    ----------
    raw : Any
        The entry as written in the file.
    place : str
        Its place for messages (``tolerances['links.0.backlash_arcmin']``).
    domain : (low, high)
        Bounds the value must respect (None: unbounded); the whole support must lie
        inside, so no sample is ever impossible.
    length : bool
        The value is a length (numbers in mm, or strings with a unit).
    open_low : bool
        The lower bound itself is excluded (e.g. an efficiency must be > 0).

    Raises
    ------
    ModelError
        Naming the place: unknown form or keys, non-finite numbers, min >= max, sd <= 0,
        a support outside the domain.
    """
    if not isinstance(raw, dict):
        raise ModelError(f"must be a mapping, one of {'; '.join(FORMS)}", place)
    if "nominal" in raw:
        dist = _nominal_form(raw, place, length)
    elif raw.get("distribution") == "uniform":
        _keys(raw, {"distribution", "min", "max"}, {"min", "max"}, place)
        low, high = (parse_number(raw[k], f"{place}.{k}", length=length) for k in ("min", "max"))
        if not low < high:
            raise ModelError(f"min must be < max, got min {low:g}, max {high:g}", place)
        dist = Distribution("uniform", low, high, (low + high) / 2.0,
                            (high - low) / math.sqrt(12.0))
    elif raw.get("distribution") == "normal":
        dist = _normal_form(raw, place, length)
    else:
        kind = raw.get("distribution")
        where = f"{place}.distribution" if kind is not None else place
        raise ModelError(f"unknown distribution {kind!r}; give one of {'; '.join(FORMS)}"
                         if kind is not None else f"give one of {'; '.join(FORMS)}", where)
    _check_domain(dist, domain, place, open_low)
    return dist


def _keys(raw: Mapping, allowed: set, required: set, place: str) -> None:
    for key in raw:
        if key not in allowed:
            raise ModelError(f"unknown field (allowed here: {', '.join(sorted(allowed))})",
                             f"{place}.{key}")
    for key in sorted(required):
        if key not in raw:
            raise ModelError(f"missing (this form needs {', '.join(sorted(required))})",
                             f"{place}.{key}")


def _normal_form(raw: Mapping, place: str, length: bool) -> Distribution:
    _keys(raw, {"distribution", "mean", "sd", "low", "high"}, {"mean", "sd"}, place)
    mean = parse_number(raw["mean"], f"{place}.mean", length=length)
    sd = parse_number(raw["sd"], f"{place}.sd", length=length)
    if sd <= 0:
        raise ModelError(f"must be > 0, got {raw['sd']!r}", f"{place}.sd")
    low = parse_number(raw["low"], f"{place}.low", length=length) if "low" in raw else -math.inf
    high = parse_number(raw["high"], f"{place}.high", length=length) if "high" in raw \
        else math.inf
    if not low < high:
        raise ModelError(f"low must be < high, got low {low:g}, high {high:g}", place)
    if not (low < mean + 8 * sd and high > mean - 8 * sd):
        raise ModelError(f"the truncation [{low:g}, {high:g}] lies more than 8 sd from the "
                         f"mean {mean:g}: practically no probability is left", place)
    return Distribution("normal", low, high, mean, sd)


def _nominal_form(raw: Mapping, place: str, length: bool) -> Distribution:
    if "grade" in raw:
        _keys(raw, {"nominal", "grade", "size", "distribution"}, {"nominal", "grade", "size"},
              place)
        tolerance = it_tolerance(raw["grade"], raw["size"], place) / 2.0
    else:
        _keys(raw, {"nominal", "tolerance", "distribution"}, {"nominal", "tolerance"}, place)
        tolerance = parse_number(raw["tolerance"], f"{place}.tolerance", minimum=0.0,
                                 length=length)
    nominal = parse_number(raw["nominal"], f"{place}.nominal", length=length)
    kind = raw.get("distribution", "normal")
    if kind not in ("normal", "uniform"):
        raise ModelError(f"must be normal (±T as ±3σ, the default) or uniform, got {kind!r}",
                         f"{place}.distribution")
    low, high = nominal - tolerance, nominal + tolerance
    if tolerance == 0:
        return Distribution("constant", nominal, nominal, nominal, 0.0)
    if kind == "uniform":
        return Distribution("uniform", low, high, nominal, tolerance / math.sqrt(3.0))
    return Distribution("normal", low, high, nominal, tolerance / 3.0)


def it_tolerance(grade: Any, size: Any, place: str) -> float:
    """ISO 286-1 standard tolerance (mm) of ``grade`` (``IT6`` or 6) for nominal size (mm).

    >>> it_tolerance("IT6", 124.8, "x")       # 120 < D <= 180 mm: IT6 = 25 µm
    0.025
    """
    match = re.fullmatch(r"(?:IT)?(\d+)", str(grade).strip(), flags=re.IGNORECASE)
    if isinstance(grade, bool) or not match or int(match.group(1)) not in GRADES:
        raise ModelError(f"grade must be one of {', '.join(f'IT{g}' for g in GRADES)}, got "
                         f"{grade!r}", f"{place}.grade")
    diameter = parse_number(size, f"{place}.size", positive=True, length=True)
    try:
        return iso_tolerance(diameter, int(match.group(1)))
    except UsageError as exc:
        raise ModelError(exc.message, f"{place}.size") from None


def _check_domain(dist: Distribution, domain: tuple, place: str, open_low: bool) -> None:
    low, high = domain
    if low is not None and (dist.low < low or (open_low and dist.low <= low)):
        bound = f"> {low:g}" if open_low else f">= {low:g}"
        if math.isinf(dist.low):
            raise ModelError(f"this value must be {bound}, but an untruncated normal reaches "
                             "any value: give low (and high) to truncate it", place)
        raise ModelError(f"this value must be {bound}, but the distribution reaches "
                         f"{dist.low:g}", place)
    if high is not None and dist.high > high:
        if math.isinf(dist.high):
            raise ModelError(f"this value must be <= {high:g}, but an untruncated normal "
                             "reaches any value: give high to truncate it", place)
        raise ModelError(f"this value must be <= {high:g}, but the distribution reaches "
                         f"{dist.high:g}", place)
