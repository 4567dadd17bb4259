"""The paper's study (Csobán 2021): maximum fluctuation over a grid, refitted.

Grid (paper Table 3; tests/data/published_values.yaml): z1 ∈ {9, 25, 43, 53, 117}, x = 0.3,
rc* = 1, and ``d``
half the ISO 286 tolerance IT5…IT9 of the pitch diameter ``m·z1``; gears with a pitch
diameter above 500 mm are left out (the paper drops m = 5, z1 = 117). The maxima are fitted
by least squares with the paper's surface ``Δi = a·d + b·d·z1^−1.5`` (Δi in %, d in mm).
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np
from scipy.linalg import lstsq

from powergraph.analyses.cycloid.fluctuation import cycloid_fluctuation
from powergraph.analyses.cycloid.report import study_text
from powergraph.errors import UsageError
from powergraph.gears.iso286 import GRADES, LARGEST_SIZE, profile_error_for_grade
from powergraph.records import record

#: Disc teeth of the paper's grid (Table 3).
PAPER_TEETH = (9, 25, 43, 53, 117)
#: The paper's fitted surfaces (Eqs. 12–15 as printed): module -> (a, b).
PAPER_FITS = {1: (6.842, 3351.9), 2: (3.464, 1720.82), 3: (2.293, 1156.47),
              5: (1.838, 680.33)}
#: Samples per contact segment in the study (the maxima are exact whatever this is).
_STUDY_POINTS = 8


@record(eq=False)
class FluctuationStudy:
    """Maximum fluctuation over the paper's grid for one module, and the refit.

    Attributes
    ----------
    teeth, grade, profile_error : ndarray
        One entry per grid point (``z1``, IT grade, ``d`` in mm).
    max_deviation_percent : ndarray
        Exact maximum ``|Δi|`` (%) at each point.
    max_deviation_percent_2deg : ndarray
        The same by the paper's 2° central differences.
    a, b : float
        Least-squares coefficients of ``Δi = a·d + b·d·z1^−1.5``.
    paper_a, paper_b : float or None
        The paper's coefficients for this module, if it gives them.
    left_out : tuple of int
        Teeth left out because ``m·z1`` exceeds 500 mm.
    """

    module: float
    shift: float
    rc: float
    teeth: np.ndarray
    grade: np.ndarray
    profile_error: np.ndarray
    max_deviation_percent: np.ndarray
    max_deviation_percent_2deg: np.ndarray
    a: float
    b: float
    paper_a: float | None
    paper_b: float | None
    left_out: tuple[int, ...]

    def fitted(self, profile_error, teeth):
        """The refitted surface ``a·d + b·d·z1^−1.5`` (%)."""
        return surface(self.a, self.b, profile_error, teeth)

    def paper_fitted(self, profile_error, teeth):
        """The paper's surface for this module (NaN when the paper gives none)."""
        if self.paper_a is None:
            return np.full(np.broadcast(profile_error, teeth).shape, np.nan)
        return surface(self.paper_a, self.paper_b, profile_error, teeth)

    def text_report(self) -> str:
        """The readable report (what the command line prints)."""
        return study_text(self)

    def plot(self, ax=None, **kwargs):
        """Max deviation against the profile error (delegates, lazily, to
        :func:`powergraph.plot.cycloid.plot_fluctuation_study`)."""
        from powergraph.plot.cycloid import plot_fluctuation_study

        return plot_fluctuation_study(self, ax=ax, **kwargs)

    def to_dict(self) -> dict:
        """Plain data for ``--json``."""
        rel = (lambda ours, theirs: None if theirs is None else ours / theirs - 1.0)
        return {
            "module": self.module, "shift": self.shift, "rc": self.rc,
            "a": self.a, "b": self.b, "paper_a": self.paper_a, "paper_b": self.paper_b,
            "a_relative_difference": rel(self.a, self.paper_a),
            "b_relative_difference": rel(self.b, self.paper_b),
            "left_out_teeth": list(self.left_out),
            "points": [
                {"teeth": int(z), "grade": f"IT{int(g)}", "profile_error": float(d),
                 "max_deviation_percent": float(v), "max_deviation_percent_2deg": float(w),
                 "fitted_percent": float(self.fitted(d, z))}
                for z, g, d, v, w in zip(self.teeth, self.grade, self.profile_error,
                                         self.max_deviation_percent,
                                         self.max_deviation_percent_2deg)],
        }


def surface(a: float, b: float, profile_error, teeth):
    """The paper's fitted form ``a·d + b·d·z1^−1.5`` (%).

    >>> round(float(surface(6.842, 3351.9, 0.1, 9)), 4)   # m = 1 at Table 2's d and z1
    13.0986
    """
    d = np.asarray(profile_error, float)
    return a * d + b * d * np.asarray(teeth, float) ** -1.5


def fluctuation_study(module: float, teeth=PAPER_TEETH, grades=GRADES, shift: float = 0.3,
                      rc: float = 1.0) -> FluctuationStudy:
    """Repeat the paper's study for one module and refit its surface by least squares.

    Parameters
    ----------
    module : float
        Module ``m`` (mm); the paper gives fits for 1, 2, 3 and 5.
    teeth : sequence of int
        Disc teeth of the grid (paper: 9, 25, 43, 53, 117).
    grades : sequence of int
        ISO 286 grades giving ``d`` (paper: IT5…IT9).

    Examples
    --------
    >>> study = fluctuation_study(1, teeth=(9, 25), grades=(5, 9))   # a small grid
    >>> study.teeth.tolist(), study.profile_error.tolist(), study.paper_a
    ([9, 9, 25, 25], [0.003, 0.018, 0.0045, 0.026], 6.842)
    """
    return _study(float(module), tuple(int(z) for z in teeth), tuple(int(g) for g in grades),
                  float(shift), float(rc))


@lru_cache(maxsize=16)
def _study(module: float, teeth: tuple[int, ...], grades: tuple[int, ...], shift: float,
           rc: float) -> FluctuationStudy:
    """The study itself, computed once per set of arguments (its arrays are read-only, so
    the cached result can be shared)."""
    kept = [int(z) for z in teeth if module * z <= LARGEST_SIZE]
    left_out = tuple(int(z) for z in teeth if module * z > LARGEST_SIZE)
    if len(kept) < 2:
        raise UsageError(f"need at least two tooth counts with m·z1 <= {LARGEST_SIZE} mm to "
                         f"fit a and b (module {module:g})")
    rows = []
    for z1 in kept:
        for grade in grades:
            d = profile_error_for_grade(module, z1, grade)
            r = cycloid_fluctuation(module, z1, d, shift, rc, points_per_segment=_STUDY_POINTS)
            rows.append((z1, grade, d, r.max_deviation_percent, r.max_deviation_percent_2deg))
    z, g, d, exact, paper_way = (_frozen(np.array(col)) for col in zip(*rows))
    (a, b), *_ = lstsq(np.column_stack([d, d * z ** -1.5]), exact)
    paper = PAPER_FITS.get(int(module)) if float(module).is_integer() else None
    return FluctuationStudy(float(module), float(shift), float(rc), _frozen(z.astype(int)),
                            _frozen(g.astype(int)), d, exact, paper_way, float(a), float(b),
                            None if paper is None else paper[0],
                            None if paper is None else paper[1], left_out)


def _frozen(values: np.ndarray) -> np.ndarray:
    values.flags.writeable = False
    return values
