"""Wang (2021)'s method and the virtual-power method side by side (docs/wang2021.md).

For the RV-40E with every mesh at 0.94 the paper's method gives 88.2 % and the
virtual-power method 28.7 %: Eq. (14) applies the cycloid–pin mesh's basic efficiency to
``P + U − L1`` (about P), while in the crank's frame, where that efficiency belongs, the
mesh passes about 39 × P. The *equivalent cycloid-mesh efficiency* is the basic efficiency
of that mesh at which the virtual-power method gives the paper's η (≈ 0.9983, a
needle-roller value).

Examples
--------
>>> from powergraph.model import load_model
>>> c = compare_methods(load_model("models/rv40e_wang2021.yaml"))                # doctest: +SKIP
>>> round(c.paper_efficiency, 6), round(c.virtual_power_efficiency, 6)  # doctest: +SKIP
(0.882062, 0.287376)
>>> round(c.equivalent_cycloid_efficiency, 6)                           # doctest: +SKIP
0.998285
"""
from __future__ import annotations

from dataclasses import field
from typing import Any

from powergraph.methods.tuning import lossless_cycloid_power
from powergraph.methods.wang2021 import Wang2021Result, paper_equations, solve_wang2021
from powergraph.model.spec import Model
from powergraph.records import record
from powergraph.result import nothing_to_draw
from powergraph.statics.result import PowerFlowResult


@record
class MethodComparison:
    """Both methods on one model, and the equivalent cycloid-mesh efficiency.

    ``rigorous`` is the virtual-power method's solve of the same model.

    ``lossless_carrier_frame_power`` is the power the cycloid–pin mesh passes in the crank's
    frame with ideal meshes (about 39 × P for the RV-40E); ``paper_cycloid_power`` the
    power Eq. (14) applies η2 to (``P + U − L1``).
    """

    paper: Wang2021Result = field(repr=False)
    rigorous: PowerFlowResult = field(repr=False)
    equivalent_cycloid_efficiency: float | None
    lossless_carrier_frame_power: float

    @property
    def paper_efficiency(self) -> float:
        return self.paper.efficiency

    @property
    def virtual_power_efficiency(self) -> float:
        return self.rigorous.efficiency

    @property
    def paper_losses(self) -> tuple[float, float]:
        """(L1, L2) by Eqs. (13)–(14)."""
        return self.paper.losses

    @property
    def virtual_power_losses(self) -> tuple[float, float]:
        """(first-stage mesh loss, cycloid–pin mesh loss) by the virtual-power method."""
        roles = self.paper.roles
        return (self.rigorous.element(roles.first_mesh).loss,
                self.rigorous.element(roles.cycloid_mesh).loss)

    @property
    def paper_cycloid_power(self) -> float:
        return self.paper.equations.cycloid_power

    @property
    def cycloid_carrier_frame_power(self) -> float:
        """Power the cycloid–pin mesh passes in the crank's frame (virtual-power solve)."""
        return self.rigorous.element(self.paper.roles.cycloid_mesh).carrier_frame_power

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Nothing to draw: raises :class:`~powergraph.result.NothingToDrawError`."""
        raise nothing_to_draw(self, "plot .paper or .rigorous (power-flow diagrams)")

    def to_dict(self) -> dict[str, Any]:
        """``{name, input_power, wang2021: {...}, virtual_power: {...},
        equivalent_cycloid_efficiency}``: ``virtual_power`` holds the virtual-power
        *method*'s numbers; its ``cycloid_mesh_power`` is the cycloid–pin mesh's power in
        the crank's frame."""
        return {"name": self.paper.name, "input_power": self.paper.input_power,
                "wang2021": {"efficiency": self.paper_efficiency,
                             "losses": list(self.paper_losses),
                             "cycloid_mesh_power": self.paper_cycloid_power},
                "virtual_power": {"efficiency": self.virtual_power_efficiency,
                                  "losses": list(self.virtual_power_losses),
                                  "cycloid_mesh_power": self.cycloid_carrier_frame_power,
                                  "lossless_cycloid_mesh_power": self.lossless_carrier_frame_power},
                "equivalent_cycloid_efficiency": self.equivalent_cycloid_efficiency}

    def text_report(self) -> str:
        """A small side-by-side table (powers in W)."""
        p1, p2 = self.paper_losses
        v1, v2 = self.virtual_power_losses
        eq = self.equivalent_cycloid_efficiency
        rows = [f"{'':<34}{'Wang (2021)':>14}{'virtual power':>16}",
                f"{'efficiency':<34}{self.paper_efficiency:>14.6f}"
                f"{self.virtual_power_efficiency:>16.6f}",
                f"{'L1, first-stage mesh (W)':<34}{p1:>14.4f}{v1:>16.4f}",
                f"{'L2, cycloid-pin mesh (W)':<34}{p2:>14.4f}{v2:>16.4f}",
                f"{'power eta2 is applied to (W)':<34}{self.paper_cycloid_power:>14.4f}"
                f"{self.cycloid_carrier_frame_power:>16.4f}",
                "equivalent cycloid-mesh efficiency: "
                + (f"{eq:.6f}" if eq is not None else "none in (0.01, 1]")]
        return "\n".join(rows)


def equivalent_cycloid_efficiency(model: Model, target: float | None = None) -> float:
    """Basic efficiency of the cycloid–pin mesh at which the virtual-power method gives
    ``target`` (default: the paper's η for ``model``), the other mesh as in the file.

    Solved with :func:`scipy.optimize.brentq` on ``model.with_link(i, efficiency=x)``.

    Parameters
    ----------
    model : Model
        An RV-type train (not changed).
    target : float, optional
        Efficiency to reach; the paper's η (Eq. 15) when omitted.

    Returns
    -------
    float

    Raises
    ------
    MethodNotApplicableError
        When the train is not RV-type.
    SolveError
        When no efficiency in (0.01, 1] reaches the target.

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> rv40e = load_model("models/rv40e_wang2021.yaml")                          # doctest: +SKIP
    >>> round(equivalent_cycloid_efficiency(rv40e), 6)                  # doctest: +SKIP
    0.998285
    """
    from powergraph.methods.rv_roles import find_rv_roles
    from powergraph.methods.tuning import efficiency_for

    roles = find_rv_roles(model)
    if target is None:
        target = paper_equations(model, roles).efficiency
    return efficiency_for(model, roles.cycloid_mesh, lambda r: r.formal_efficiency, target)


def compare_methods(model: Model) -> MethodComparison:
    """Wang (2021)'s η and losses beside the virtual-power method's, for one model.

    Parameters
    ----------
    model : Model
        An RV-type train (not changed).

    Returns
    -------
    MethodComparison

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> c = compare_methods(load_model("models/rv40e_wang2021.yaml"))   # doctest: +SKIP
    >>> print(c.text_report())                                  # doctest: +SKIP
                                         Wang (2021)   virtual power
    efficiency                              0.882062        0.287376
    L1, first-stage mesh (W)                136.2000        135.0744
    L2, cycloid-pin mesh (W)                131.5203       1482.5829
    power eta2 is applied to (W)           2192.0051      24709.7145
    equivalent cycloid-mesh efficiency: 0.998285
    """
    from powergraph.errors import SolveError
    from powergraph.statics import solve

    paper = solve_wang2021(model, realise_flows=False)
    vp = paper.virtual_power_result if paper.virtual_power_result is not None else solve(model)
    try:
        equivalent: float | None = equivalent_cycloid_efficiency(model, paper.efficiency)
    except SolveError:
        equivalent = None
    return MethodComparison(paper=paper, rigorous=vp,
                            equivalent_cycloid_efficiency=equivalent,
                            lossless_carrier_frame_power=lossless_cycloid_power(
                                model, paper.roles.cycloid_mesh))
