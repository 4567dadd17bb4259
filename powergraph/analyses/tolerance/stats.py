"""Summaries of the sampled outputs, specifications, yields and their confidence intervals.

A specification is ``NAME OP VALUE[UNIT]``: ``lost_motion<=1arcmin``, ``lost_motion<=30"``,
``fluctuation<=0.5%``, ``efficiency>=0.85`` (or ``>=85%``). OP is ``<=``, ``<``, ``>=`` or
``>``. The yield of a specification is the fraction of units that meet it; a unit whose
output could not be computed (NaN: an efficiency whose power directions do not settle)
does not meet it. The 95 % interval is Wilson's score interval (Wilson 1927), which keeps
its coverage near 0 and 1 where the normal approximation fails:

    (p̂ + z²/2n ± z·√(p̂(1 − p̂)/n + z²/4n²)) / (1 + z²/n),   z = 1.959964.

Examples
--------
>>> s = parse_spec("lost_motion<=1arcmin")
>>> s.output, s.op, s.value
('lost_motion_arcmin', '<=', 1.0)
>>> [round(x, 4) for x in wilson_interval(95, 100)]
[0.8882, 0.9785]
"""
from __future__ import annotations

import math
import re

import numpy as np

from powergraph.errors import UsageError
from powergraph.records import record

#: Two-sided 95 % normal quantile.
Z95 = 1.959963984540054
QUANTILES = {"p50": 0.5, "p95": 0.95, "p99_73": 0.9973}
#: spec name -> (output, {unit: factor to the output's unit})
SPEC_OUTPUTS = {
    "lost_motion": ("lost_motion_arcmin", {"": 1.0, "arcmin": 1.0, "'": 1.0, "′": 1.0,
                                           "arcsec": 1 / 60, '"': 1 / 60, "″": 1 / 60,
                                           "deg": 60.0}),
    "fluctuation": ("fluctuation_percent", {"%": 1.0, "": 1.0}),
    "efficiency": ("efficiency", {"": 1.0, "%": 0.01}),
}
_SPEC = re.compile(r"^\s*([a-z_]+)\s*(<=|>=|<|>)\s*([-+0-9.eE]+)\s*(\S*)\s*$")


@record
class Spec:
    """One specification: ``output op value`` (value in the output's own unit)."""

    text: str
    output: str
    op: str
    value: float

    def met(self, values: np.ndarray) -> np.ndarray:
        """Which units meet it (NaN never does)."""
        compare = {"<=": np.less_equal, "<": np.less, ">=": np.greater_equal,
                   ">": np.greater}[self.op]
        return compare(values, self.value)


def parse_spec(text: str) -> Spec:
    """Parse ``NAME OP VALUE[UNIT]`` (see the module docstring).

    Raises
    ------
    UsageError
        An unknown name or unit, or not of that form.
    """
    match = _SPEC.match(text or "")
    names = ", ".join(SPEC_OUTPUTS)
    if not match:
        raise UsageError(f"--spec {text!r}: expected NAME<=VALUE[UNIT] (NAME one of {names}), "
                         'e.g. "lost_motion<=1arcmin"')
    name, op, number, unit = match.groups()
    if name not in SPEC_OUTPUTS:
        raise UsageError(f"--spec {text!r}: unknown output {name!r} (one of {names})")
    output, units = SPEC_OUTPUTS[name]
    if unit not in units:
        raise UsageError(f"--spec {text!r}: unit {unit!r} does not fit {name} (use "
                         f"{', '.join(repr(u) for u in units if u)})")
    try:
        value = float(number)
    except ValueError:
        raise UsageError(f"--spec {text!r}: {number!r} is not a number") from None
    if not math.isfinite(value):
        raise UsageError(f"--spec {text!r}: the limit must be finite")
    return Spec(text.strip(), output, op, value * units[unit])


def wilson_interval(successes: int, n: int, z: float = Z95) -> tuple[float, float]:
    """Wilson score interval of a binomial proportion (95 % by default)."""
    if n <= 0:
        raise UsageError("the yield needs at least one sample")
    p = successes / n
    centre = p + z * z / (2 * n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    scale = 1 + z * z / n
    low = 0.0 if successes == 0 else max(0.0, (centre - half) / scale)
    high = 1.0 if successes == n else min(1.0, (centre + half) / scale)
    return low, high


@record
class Yield:
    """The fraction of units meeting a specification, with its 95 % Wilson interval."""

    spec: Spec
    met: int
    samples: int

    @property
    def fraction(self) -> float:
        return self.met / self.samples

    @property
    def interval(self) -> tuple[float, float]:
        return wilson_interval(self.met, self.samples)

    def to_dict(self) -> dict:
        low, high = self.interval
        return {"fraction": self.fraction, "low": low, "high": high, "met": self.met,
                "samples": self.samples}


def summary(values: np.ndarray) -> dict[str, float]:
    """mean, sd, p50, p95, p99_73, max of the finite values; ``failed`` counts NaNs."""
    finite = values[np.isfinite(values)]
    stats = {"mean": math.nan, "sd": math.nan, **{k: math.nan for k in QUANTILES},
             "max": math.nan}
    if finite.size:
        q = np.quantile(finite, list(QUANTILES.values()))
        stats.update(mean=float(np.mean(finite)), sd=float(np.std(finite, ddof=1))
                     if finite.size > 1 else 0.0, max=float(np.max(finite)),
                     **{k: float(v) for k, v in zip(QUANTILES, q)})
        stats["min"] = float(np.min(finite))
    stats["failed"] = int(values.size - finite.size)
    return stats
