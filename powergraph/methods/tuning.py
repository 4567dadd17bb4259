"""Find the basic efficiency of one mesh at which a virtual-power solve meets a target.

Used for the *equivalent cycloid-mesh efficiency* (the basic efficiency of the cycloid–pin
mesh at which the rigorous method gives the paper's η) and for the mechanically consistent
realisation of the paper's losses (:mod:`powergraph.methods.wang2021`).

Examples
--------
>>> from powergraph.model import load_model
>>> model = load_model("models/rv40e_wang2021.yaml")                           # doctest: +SKIP
>>> x = efficiency_for(model, 1, lambda r: r.formal_efficiency, 0.882061)  # doctest: +SKIP
>>> round(x, 6)                                                       # doctest: +SKIP
0.998285
"""
from __future__ import annotations

from typing import Callable

from powergraph.errors import SolveError
from powergraph.model.spec import Model
from powergraph.statics.result import PowerFlowResult

#: Trial lower ends of the bracket, tried in turn from the top.
_LOWER = (0.99, 0.9, 0.5, 0.1, 0.01)


def solve_with(model: Model, link: int, efficiency: float) -> PowerFlowResult:
    """Virtual-power solve of a copy of ``model`` with ``links[link]`` at ``efficiency``."""
    from powergraph.statics import solve

    return solve(model.with_link(link, efficiency=float(efficiency)))


def efficiency_for(model: Model, link: int, measure: Callable[[PowerFlowResult], float],
                   target: float, xtol: float = 1e-14) -> float:
    """Basic efficiency ``x`` of ``links[link]`` with ``measure(solve(model')) = target``.

    ``measure`` must fall as the efficiency rises (a loss) or rise with it (an
    efficiency); the root is bracketed between 1 and the first of 0.99, 0.9, 0.5, 0.1,
    0.01 where the sign changes, then found with :func:`scipy.optimize.brentq`.

    Parameters
    ----------
    model : Model
        The train (not changed).
    link : int
        Index of the mesh whose basic efficiency is varied.
    measure : callable
        Quantity of the solved result to match (e.g. ``lambda r: r.efficiency``).
    target : float
        The value to reach.
    xtol : float
        Absolute tolerance on the efficiency.

    Returns
    -------
    float
        The basic efficiency, in (0, 1].

    Raises
    ------
    SolveError
        When no efficiency in (0.01, 1] reaches the target.

    Examples
    --------
    >>> from powergraph.model import model_from_dict
    >>> pair = model_from_dict({"name": "pair", "components": {0: {"role": "frame"},
    ...     1: {"teeth": 20}, 2: {"teeth": 40}}, "links": [{"type": "mesh", "between": [1, 2]}],
    ...     "ports": [{"component": 1, "role": "input", "power": 100},
    ...               {"component": 2, "role": "output"}]})
    >>> round(efficiency_for(pair, 0, lambda r: r.efficiency, 0.97), 12)
    0.97
    """
    from scipy.optimize import brentq

    def gap(x: float) -> float:
        return measure(solve_with(model, link, x)) - target

    top = gap(1.0)
    if abs(top) <= 1e-12 * max(abs(target), 1.0):
        return 1.0
    for lower in _LOWER:
        try:
            low = gap(lower)
        except SolveError:
            continue
        if low == 0.0:
            return lower
        if (low < 0) != (top < 0):
            return float(brentq(gap, lower, 1.0, xtol=xtol, rtol=1e-15))
    raise SolveError(f"no basic efficiency of links[{link}] in (0.01, 1] gives {target!r} "
                     f"by the virtual-power method (at 1 it gives {top + target!r})")


def lossless_cycloid_power(model: Model, cycloid_mesh: int) -> float:
    """Power the cycloid–pin mesh passes in its carrier's frame with ideal meshes (W).

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> rv40e = load_model("models/rv40e_wang2021.yaml")                          # doctest: +SKIP
    >>> round(lossless_cycloid_power(rv40e, 1) / 2270, 4)               # doctest: +SKIP
    38.6777
    """
    from powergraph.statics import solve

    return solve(model.with_mesh_efficiency(1.0)).element(cycloid_mesh).carrier_frame_power
