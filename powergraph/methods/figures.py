"""Data of Wang (2021)'s Figs. 12–13, by the paper's method and by the virtual-power method.

Each function returns a :class:`FigureData` (curves as read-only arrays, axis labels and a
caption that says what each curve is); :mod:`powergraph.plot.wang2021` draws it and
``scripts/wang2021_figures.py`` writes the PNG/SVG files. The paper's curve evaluates its
equations on a copy of the model per point (β and α come from the speeds); each
virtual-power curve is one call of the compiled sweep (:mod:`powergraph.analyses.sweep`)
over the same grid.

- Fig. 12: η against the single-pair mesh efficiency (0.90–1.00);
- Fig. 12b: the equivalent cycloid-mesh efficiency against the same;
- Fig. 13: η against the RV ratio ``1 + z2·z5/z1``, varying z5 with z4 = z5 − 1, and
  separately varying z2 (so z2/z1).

By the paper's equations ``η = η1 − (η1 + 1/β)(1 − η2)`` with ``β = z4/(z5 − z4)``: η
*rises* slightly with z4 (0.88153 at z4 = 29, 0.88206 at 39, 0.88238 at 49) and does not
depend on z2/z1, while the paper's text says η falls as the ratio grows. The
virtual-power η does fall. We plot what the equations give (tests/data/published_values.yaml).

Examples
--------
>>> from powergraph.model import load_model
>>> rv40e = load_model("models/rv40e_wang2021.yaml")                      # doctest: +SKIP
>>> fig = cycloid_ratio_curves(rv40e, z5_values=[30, 40, 50])    # doctest: +SKIP
>>> [round(float(y), 5) for y in fig.curve("wang2021").y]        # doctest: +SKIP
[0.88153, 0.88206, 0.88238]
"""
from __future__ import annotations

import dataclasses
from types import MappingProxyType
from typing import Any, Callable, Iterable, Mapping

import numpy as np

from powergraph.errors import SolveError
from powergraph.model.spec import Model
from powergraph.records import record

NEEDLE_EFFICIENCY = 0.998   # needle-roller pin mesh (docs/theory.md)


def _frozen(values: Iterable[float]) -> np.ndarray:
    array = np.array(list(values), dtype=float)
    array.setflags(write=False)
    return array


@record
class Curve:
    """One curve: ``y`` against ``x`` by ``method`` ("wang2021" or "virtual-power")."""

    key: str
    label: str
    method: str
    x: np.ndarray
    y: np.ndarray

    def to_dict(self) -> dict[str, Any]:
        return {"key": self.key, "label": self.label, "method": self.method,
                "x": self.x.tolist(), "y": self.y.tolist()}


@record
class Mark:
    """An annotated point (e.g. a published reference value on a curve)."""

    curve: str
    x: float
    y: float
    text: str


@record
class FigureData:
    """Everything a figure shows; the plot functions compute nothing.

    Follows the result protocol :class:`powergraph.result.Result`.
    """

    key: str
    title: str
    xlabel: str
    ylabel: str
    curves: tuple[Curve, ...]
    caption: str
    marks: tuple[Mark, ...] = ()

    def curve(self, key: str) -> Curve:
        """The curve called ``key``."""
        return next(c for c in self.curves if c.key == key)

    def text_report(self) -> str:
        """Title, axes, caption and every curve's points, one per line."""
        lines = [self.title, f"x: {self.xlabel}; y: {self.ylabel}", self.caption, ""]
        for curve in self.curves:
            lines.append(f"{curve.label} ({curve.method})")
            lines += [f"  {x:>10.6g}  {y:>10.6g}" for x, y in zip(curve.x, curve.y)]
        return "\n".join(lines)

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Draw every curve (delegates, lazily, to :func:`powergraph.plot.wang2021.plot_figure`)."""
        from powergraph.plot.wang2021 import plot_figure

        return plot_figure(self, ax=ax, **kwargs)

    def to_dict(self) -> dict[str, Any]:
        """``{key, title, xlabel, ylabel, caption, curves: [{key, label, method, x, y}],
        marks}``; a curve's ``method`` is "wang2021" or "virtual-power"."""
        return {"key": self.key, "title": self.title, "xlabel": self.xlabel,
                "ylabel": self.ylabel, "caption": self.caption,
                "curves": [c.to_dict() for c in self.curves],
                "marks": [dataclasses.asdict(m) for m in self.marks]}


def with_teeth(model: Model, teeth: Mapping[str, int]) -> Model:
    """A copy of ``model`` with the teeth of some components changed (ids as strings).

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> rv40e = load_model("models/rv40e_wang2021.yaml")                          # doctest: +SKIP
    >>> with_teeth(rv40e, {"5": 50}).components["5"].teeth               # doctest: +SKIP
    50
    """
    components = dict(model.components)
    for cid, z in teeth.items():
        components[cid] = dataclasses.replace(components[cid], teeth=int(z))
    return dataclasses.replace(model, components=MappingProxyType(components))


def _marks_at(curves: tuple[Curve, ...], x0: float, fmt: str) -> tuple[Mark, ...]:
    """A mark on every curve at ``x == x0`` (if the grid has it), its value as ``fmt``."""
    marks = []
    for curve in curves:
        hits = np.flatnonzero(np.isclose(curve.x, x0, rtol=0, atol=1e-9))
        if hits.size:
            y = float(curve.y[hits[0]])
            marks.append(Mark(curve.key, float(curve.x[hits[0]]), y, format(y, fmt)))
    return tuple(marks)


def _paper(model: Model) -> float:
    from powergraph.methods.wang2021 import paper_equations

    return paper_equations(model).efficiency


def _roles(model: Model):
    from powergraph.methods.rv_roles import find_rv_roles

    return find_rv_roles(model)


def _by_virtual_power_method(model: Model, values: Mapping[str, Any]) -> Any:
    """The virtual-power method over a grid, by the compiled sweep (one call per curve)."""
    from powergraph.analyses.sweep import sweep

    result = sweep(model, values, quiet=True)
    if not np.all(result.converged):
        raise SolveError(f"the power directions did not settle for some points of {values}")
    return result


def _three_curves(model: Model, variants: list[Model], values: Mapping[str, Any],
                  x: np.ndarray | None, needle: float, paper_label: str,
                  both_label: str) -> tuple[Curve, ...]:
    """The paper's η (its closed equations, per variant), the virtual-power η and the
    virtual-power η with a needle mesh (compiled sweeps over ``values``). ``x=None``
    plots against the ratio."""
    roles = _roles(model)
    paper = _frozen(_paper(m) for m in variants)
    rigorous = _by_virtual_power_method(model, values)
    needle_values = {**values, f"links.{roles.cycloid_mesh}.efficiency": needle}
    with_needle = _by_virtual_power_method(model, needle_values)
    x = _frozen(rigorous.ratio) if x is None else x
    return (Curve("wang2021", paper_label, "wang2021", x, paper),
            Curve("virtual-power", both_label, "virtual-power", x, _frozen(rigorous.efficiency)),
            Curve("virtual-power-needle", f"virtual-power method, cycloid-pin mesh {needle}",
                  "virtual-power", x, _frozen(with_needle.efficiency)))


def mesh_efficiency_curves(model: Model, efficiencies: Iterable[float] | None = None,
                           needle: float = NEEDLE_EFFICIENCY) -> FigureData:
    """Fig. 12: η against the single-pair mesh efficiency, by both methods.

    Parameters
    ----------
    model : Model
        An RV-type train (the RV-40E for the paper's figure); not changed.
    efficiencies : iterable of float, optional
        Single-pair mesh efficiencies (default 0.90 to 1.00 by 0.005).
    needle : float
        Cycloid–pin mesh efficiency of the third curve.

    Returns
    -------
    FigureData
        Curves ``wang2021`` (Eqs. 13–15, η1 = η2 = x), ``virtual-power`` (both meshes at x)
        and ``virtual-power-needle`` (first stage x, cycloid–pin mesh ``needle``).

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> fig = mesh_efficiency_curves(load_model("models/rv40e_wang2021.yaml"), [0.94])  # doctest: +SKIP
    >>> round(float(fig.curve("virtual-power").y[0]), 6)                # doctest: +SKIP
    0.287376
    """
    x = _frozen(np.linspace(0.90, 1.00, 21) if efficiencies is None else efficiencies)
    roles = _roles(model)
    variants = [model.with_mesh_efficiency(float(e)) for e in x]
    values = {f"links.{roles.first_mesh}.efficiency": x,
              f"links.{roles.cycloid_mesh}.efficiency": x}
    curves = _three_curves(model, variants, values, x, needle,
                           "Wang (2021), Eqs. 13-15, both meshes at x",
                           "virtual-power method, both meshes at x")
    caption = (f"Efficiency of {model.name} against the single-pair mesh efficiency x. "
               "Solid: the paper's method, Eqs. (13)-(15), with eta1 = eta2 = x (its Fig. 12). "
               "Dashed: the virtual-power method, both meshes at x. Dotted: the virtual-power "
               f"method, first-stage mesh at x, cycloid-pin (needle) mesh at {needle}. The "
               "paper applies eta2 to about P; in the crank's frame the cycloid-pin mesh "
               "passes about 39 P, so the rigorous method needs a needle-roller pin mesh to "
               "come near the paper's values.")
    marks = _marks_at(curves, model.links[roles.first_mesh].efficiency, ".2%")
    return FigureData("fig12_mesh_efficiency", "Fig. 12: efficiency vs mesh efficiency",
                      "single-pair mesh efficiency x", "RV efficiency", curves, caption, marks)


def equivalent_efficiency_curve(model: Model,
                                efficiencies: Iterable[float] | None = None) -> FigureData:
    """Fig. 12b: the cycloid–pin efficiency at which the virtual-power method gives the
    paper's η, against the single-pair mesh efficiency x (first stage at x).

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> fig = equivalent_efficiency_curve(load_model("models/rv40e_wang2021.yaml"), [0.94])  # doctest: +SKIP
    >>> round(float(fig.curves[0].y[0]), 6)                             # doctest: +SKIP
    0.998285
    """
    from powergraph.methods.method_comparison import equivalent_cycloid_efficiency

    x = _frozen(np.linspace(0.90, 1.00, 21) if efficiencies is None else efficiencies)
    variants = [model.with_mesh_efficiency(float(e)) for e in x]
    y = _frozen(equivalent_cycloid_efficiency(m) for m in variants)
    curve = Curve("equivalent", "equivalent cycloid-pin mesh efficiency", "virtual-power",
                  x, y)
    caption = ("Basic efficiency of the cycloid-pin mesh at which the virtual-power method "
               f"reproduces the paper's efficiency of {model.name}, the first-stage mesh at "
               "x and the paper's eta1 = eta2 = x. The paper's single x is worth a "
               "needle-roller-class pin mesh.")
    first = model.links[_roles(model).first_mesh].efficiency
    return FigureData("fig12_equivalent_cycloid_efficiency",
                      "Equivalent cycloid-pin mesh efficiency", "single-pair mesh efficiency x",
                      "equivalent cycloid-pin efficiency", (curve,), caption,
                      _marks_at((curve,), first, ".6f"))


def _ratio_curves(model: Model, variants: list[Model], values: Mapping[str, Any],
                  needle: float) -> tuple[Curve, ...]:
    roles = _roles(model)
    eta1 = model.links[roles.first_mesh].efficiency
    eta2 = model.links[roles.cycloid_mesh].efficiency
    return _three_curves(model, variants, values, None, needle,
                         f"Wang (2021), Eqs. 13-15 (eta1 = {eta1}, eta2 = {eta2})",
                         f"virtual-power method (eta1 = {eta1}, eta2 = {eta2})")


def cycloid_ratio_curves(model: Model, z5_values: Iterable[int] | None = None,
                         needle: float = NEEDLE_EFFICIENCY,
                         reference_z4: Iterable[int] = (29, 39, 49)) -> FigureData:
    """Fig. 13 (cycloid stage): η against the RV ratio, varying z5 with z4 = z5 − 1.

    Parameters
    ----------
    model : Model
        An RV-type train (not changed); the other teeth and efficiencies as in it.
    z5_values : iterable of int, optional
        Pin-gear teeth (default 20 to 60).
    needle : float
        Cycloid–pin mesh efficiency of the third curve.
    reference_z4 : iterable of int
        Cycloid teeth whose paper value is marked (tests/data/published_values.yaml).

    Returns
    -------
    FigureData

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> fig = cycloid_ratio_curves(load_model("models/rv40e_wang2021.yaml"), [40])  # doctest: +SKIP
    >>> paper = fig.curve("wang2021")                                    # doctest: +SKIP
    >>> round(float(paper.x[0]), 9), round(float(paper.y[0]), 6)        # doctest: +SKIP
    (121.0, 0.882062)
    """
    roles = _roles(model)
    z5s = list(range(20, 61) if z5_values is None else z5_values)
    variants = [with_teeth(model, {roles.pin_gear: z5, roles.cycloid: z5 - 1}) for z5 in z5s]
    values = {f"components.{roles.pin_gear}.teeth": np.array(z5s),
              f"components.{roles.cycloid}.teeth": np.array(z5s) - 1}
    curves = _ratio_curves(model, variants, values, needle)
    paper = curves[0]
    marks = tuple(Mark("wang2021", float(paper.x[z5s.index(z4 + 1)]),
                       float(paper.y[z5s.index(z4 + 1)]),
                       f"z4 = {z4}: {paper.y[z5s.index(z4 + 1)]:.5f}")
                  for z4 in reference_z4 if z4 + 1 in z5s)
    caption = (f"Efficiency of {model.name} against its ratio 1 + z2 z5/z1, varying the pin "
               "gear z5 with the cycloid z4 = z5 - 1. Solid: the paper's Eqs. (13)-(15), "
               "eta = eta1 - (eta1 + 1/beta)(1 - eta2) with beta = z4: it RISES slightly "
               "with the ratio (0.88153 at z4 = 29, 0.88206 at 39, 0.88238 at 49), although "
               "the paper's text says efficiency falls as the ratio grows; we plot what its "
               "equations give. Dashed: the virtual-power method, same meshes; dotted: with "
               f"a {needle} needle mesh. Both fall with the ratio, as the paper's text says.")
    return FigureData("fig13_ratio_cycloid_teeth",
                      "Fig. 13: efficiency vs ratio (z5, z4 = z5 - 1)",
                      "RV ratio i = 1 + z2 z5 / z1", "RV efficiency", curves, caption, marks)


def first_stage_ratio_curves(model: Model, z2_values: Iterable[int] | None = None,
                             needle: float = NEEDLE_EFFICIENCY) -> FigureData:
    """Fig. 13 (first stage): η against the RV ratio, varying z2 (so z2/z1).

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> fig = first_stage_ratio_curves(load_model("models/rv40e_wang2021.yaml"), [24, 36])  # doctest: +SKIP
    >>> [round(float(y), 6) for y in fig.curve("wang2021").y]           # doctest: +SKIP
    [0.882062, 0.882062]
    """
    roles = _roles(model)
    z2s = list(range(12, 61, 2) if z2_values is None else z2_values)
    variants = [with_teeth(model, {roles.planet_gear: z2}) for z2 in z2s]
    values = {f"components.{roles.planet_gear}.teeth": np.array(z2s)}
    curves = _ratio_curves(model, variants, values, needle)
    z1 = model.components[roles.input_gear].teeth
    caption = (f"Efficiency of {model.name} against its ratio 1 + z2 z5/z1, varying the "
               f"planet gear z2 (z1 = {z1}, so z2/z1 from {z2s[0] / z1:.3g} to "
               f"{z2s[-1] / z1:.3g}). Solid: the paper's Eqs. (13)-(15) do not depend on "
               "z2/z1 at all (beta = z4/(z5 - z4)): a flat line. Dashed: the virtual-power "
               f"method, same meshes; dotted: with a {needle} needle mesh.")
    return FigureData("fig13_ratio_first_stage", "Fig. 13: efficiency vs ratio (z2/z1)",
                      "RV ratio i = 1 + z2 z5 / z1", "RV efficiency", curves, caption)


#: The figures the script writes, in order: name -> function of the model.
FIGURES: dict[str, Callable[[Model], FigureData]] = {
    "fig12_mesh_efficiency": mesh_efficiency_curves,
    "fig12_equivalent_cycloid_efficiency": equivalent_efficiency_curve,
    "fig13_ratio_cycloid_teeth": cycloid_ratio_curves,
    "fig13_ratio_first_stage": first_stage_ratio_curves,
}
