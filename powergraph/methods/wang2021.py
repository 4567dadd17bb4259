"""Wang (2021): the split/virtual power efficiency of an RV reducer (docs/wang2021.md).

Wang (2021), "Efficiency analysis of RV reducers by the split/virtual power method".

From the speeds of the graph (roles found by :func:`~powergraph.methods.rv_roles.find_rv_roles`,
the paper's numbering in brackets):

- split power ratio ``β = P/(P − V) = −w2/w4`` (Eq. 8) gives the split power ``V``;
- virtual power ratio ``α = (w4 − w3)/w4 = (P + U)/(P − V)`` (Eq. 12) gives ``U``;
- ``L1 = P(1 − η1)`` (Eq. 13), ``L2 = (P + U − L1)(1 − η2)`` (Eq. 14),
  ``η = (P − L1 − L2)/P`` (Eq. 15).

For the RV-40E (Table 1, every mesh 0.94) this is 88.2 %; the rigorous virtual-power
method gives 28.7 % for the same file, because it applies η2 to the power the cycloid–pin
mesh really passes in the crank's frame, about 39 × P, not P + U − L1 (docs/theory.md).
:func:`powergraph.methods.method_comparison.compare_methods` puts the two side by side.

What the result reports besides the paper's numbers (the paper does not give them):

- ``meshes``: per mesh, the power the paper applies the basic efficiency to (``P`` for the
  first stage, Eq. 13; ``P + U − L1`` for the cycloid–pin mesh, Eq. 14), its loss (L1, L2)
  and the driver the paper's Figs. 8–9 draw (the input gear; the fixed pin gear, since the
  cycloid receives the power in the crank's frame);
- ``torques``: consistent with the paper's η: ``P/w_in`` on the input, ``−ηP/w_out`` on
  the output and the rest on the frame;
- ``flows``: the paper's Fig. 10 with ``V`` cannot balance once losses are drawn (for the
  RV-40E ``P − L1 < V``), so ``flows`` is the one mechanically consistent graph with the
  paper's losses: a virtual-power solve whose two basic efficiencies are tuned so that it
  loses exactly L1 in the first-stage mesh and L2 in the cycloid–pin mesh (every body in
  equilibrium, every node balanced; ``realised_efficiencies``). The paper's lossless split
  (its Fig. 5, with ``V``) is ``split_flows``;
- ``self_locking``: by the virtual-power method (formal efficiency <= 0, docs/format.md).

Examples
--------
>>> from powergraph.model import load_model
>>> result = solve_wang2021(load_model("models/rv40e_wang2021.yaml"))           # doctest: +SKIP
>>> round(result.split_power, 4), round(result.paper_virtual_power, 5)       # doctest: +SKIP
(2211.7949, 58.20513)
>>> [round(x, 5) for x in result.losses], round(result.efficiency, 6)  # doctest: +SKIP
([136.2, 131.52031], 0.882062)
"""
from __future__ import annotations

from dataclasses import field
from typing import Any

from powergraph.errors import MethodNotApplicableError, SolveError, StaticsError
from powergraph.kinematics import Kinematics, solve_speeds
from powergraph.methods.rv_roles import NEEDS, RVRoles, find_rv_roles
from powergraph.methods.wang2021_equations import PaperEquations
from powergraph.methods.wang2021_report import result_to_dict, split_flows, text_report
from powergraph.model.spec import Model
from powergraph.records import record
from powergraph.statics.flow import Flow
from powergraph.statics.friction import loss_block_places
from powergraph.statics.result import PowerFlowResult


@record
class PaperMesh:
    """One mesh as the paper's method sees it.

    ``applied_power`` is the power the paper applies the mesh's basic efficiency to
    (``P`` for the first stage, Eq. 13; ``P + U − L1`` for the cycloid–pin mesh, Eq. 14).
    """

    link: int
    role: str            # "first stage" (mesh 1-2) or "cycloid-pin" (mesh 4-5)
    a: str
    b: str
    carrier: str
    driver: str
    efficiency: float
    applied_power: float
    loss: float


@record
class Wang2021Result:
    """The paper's method on one model; follows :class:`powergraph.result.Result`.

    ``to_dict()`` is the ``solve --method wang2021 --json`` object (docs/format.md).
    """

    model: Model = field(repr=False, compare=False)
    kinematics: Kinematics = field(repr=False)
    roles: RVRoles
    equations: PaperEquations
    virtual_power_result: PowerFlowResult | None = field(default=None, repr=False)
    realisation: PowerFlowResult | None = field(default=None, repr=False)
    realised_efficiencies: tuple[float, float] | None = None
    method: str = "wang2021"

    # --- the paper's numbers ---------------------------------------------------------
    @property
    def name(self) -> str:
        return self.model.name

    @property
    def dof(self) -> int:
        return self.kinematics.dof

    @property
    def ratio(self) -> float | None:
        """Input speed / output speed."""
        return self.kinematics.ratio

    @property
    def beta(self) -> float:
        """Split power ratio ``−w2/w4`` (Eq. 8)."""
        return self.equations.beta

    @property
    def alpha(self) -> float:
        """Virtual power ratio ``(w4 − w3)/w4`` (Eq. 12)."""
        return self.equations.alpha

    @property
    def input_power(self) -> float:
        """P (W)."""
        return self.equations.input_power

    @property
    def split_power(self) -> float:
        """V (W), Eqs. (8)–(9)."""
        return self.equations.split_power

    @property
    def paper_virtual_power(self) -> float:
        """The paper's "virtual power" U (W), Eq. (12) (JSON key ``virtual_power``)."""
        return self.equations.paper_virtual_power

    @property
    def efficiency(self) -> float:
        """η by Eq. (15)."""
        return self.equations.efficiency

    @property
    def losses(self) -> tuple[float, float]:
        """(L1 of the first-stage mesh, L2 of the cycloid–pin mesh)."""
        return self.equations.first_loss, self.equations.cycloid_loss

    @property
    def total_loss(self) -> float:
        return sum(self.losses)

    @property
    def output_power(self) -> float:
        return self.input_power - self.total_loss

    @property
    def virtual_power_efficiency(self) -> float | None:
        """η of the same model by the virtual-power method (None if it failed)."""
        vp = self.virtual_power_result
        return vp.efficiency if vp is not None else None

    @property
    def self_locking(self) -> bool:
        """Self-locking by the virtual-power method (formal efficiency <= 0), or the paper's
        η <= 0 if that method failed."""
        vp = self.virtual_power_result
        return vp.self_locking if vp is not None else not self.efficiency > 0.0

    # --- speeds, torques, meshes, flows --------------------------------------------
    @property
    def speeds(self) -> dict[str, float]:
        return {c: self.kinematics.speed(c) for c in self.model.components}

    @property
    def torques(self) -> dict[str, float]:
        """External torques consistent with the paper's η: input, output, frame (N·m)."""
        roles, kin = self.roles, self.kinematics
        t_in = self.input_power / kin.speed(roles.input_gear)
        t_out = -self.output_power / kin.speed(roles.output_component)
        return {roles.input_gear: t_in, roles.output_component: t_out,
                self.model.frame: -(t_in + t_out)}

    @property
    def meshes(self) -> tuple[PaperMesh, ...]:
        """Both meshes in file order, with the paper's powers and losses."""
        links, roles, eq = self.model.links, self.roles, self.equations
        first = links[roles.first_mesh]
        second = links[roles.cycloid_mesh]
        out = [PaperMesh(first.index, "first stage", *first.between, first.carrier,
                         roles.input_gear, eq.eta1, eq.input_power, eq.first_loss),
               PaperMesh(second.index, "cycloid-pin", *second.between, second.carrier,
                         roles.pin_gear, eq.eta2, eq.cycloid_power, eq.cycloid_loss)]
        return tuple(sorted(out, key=lambda m: m.link))

    def flows(self) -> list[Flow]:
        """Ground-frame flows of the consistent realisation of the paper's losses."""
        return self.realisation.flows() if self.realisation is not None else []

    @property
    def circulating_power(self) -> float:
        from powergraph.statics.flow import circulating_power

        return circulating_power(self.flows())

    def split_flows(self) -> list[Flow]:
        """The paper's Fig. 5: the lossless split of P at the planet/crank body into V."""
        return split_flows(self)

    def to_dict(self) -> dict[str, Any]:
        """The ``solve --json`` keys plus ``split_power`` (V), ``virtual_power`` (the
        paper's U, :attr:`paper_virtual_power`), ``losses`` ([L1, L2]), ``beta``,
        ``alpha`` and more; per mesh, ``virtual_power`` is the power the paper applies
        the mesh's efficiency to (:attr:`PaperMesh.applied_power`)."""
        return result_to_dict(self)

    def text_report(self) -> str:
        """The readable report of ``powergraph solve MODEL --method wang2021``."""
        return text_report(self)

    def plot(self, ax: Any = None, *, frame: str | None = None, **kwargs: Any):
        """Draw the flow graph of the paper's losses (``flows``), seen from ``frame``.

        Delegates, lazily, to :func:`powergraph.plot.power_flow.plot_power_flow`.
        """
        from powergraph.plot.power_flow import plot_power_flow

        return plot_power_flow(self, frame=frame, ax=ax, **kwargs)


def _refuse(found: str) -> MethodNotApplicableError:
    return MethodNotApplicableError(f"{NEEDS}; {found}")


def split_ratios(kin: Kinematics, roles: RVRoles) -> tuple[float, float]:
    """``β = −w2/w4`` (Eq. 8) and ``α = (w4 − w3)/w4`` (Eq. 12) from the speeds.

    ``w2`` is the planet gear, ``w3`` the carrier of the cycloid mesh (the same body in an
    RV reducer) and ``w4`` the cycloid gear.
    """
    w4 = kin.speed(roles.cycloid)
    if w4 == 0.0:
        raise _refuse("the cycloid gear does not turn (w4 = 0), so β = −w2/w4 is undefined")
    w2 = kin.speed(roles.planet_gear)
    w3 = kin.body_speeds[roles.planet_body]
    return -w2 / w4, (w4 - w3) / w4


def _port_load(model: Model, kin: Kinematics, role: str) -> float | None:
    """Power a port feeds in (input) or takes out (output), if the file gives one."""
    port = (model.inputs if role == "input" else model.outputs)[0]
    if port.power is not None:
        return port.power
    if port.torque is not None:
        fed = port.torque * kin.speed(port.component)
        return fed if role == "input" else -fed
    return None


def _input_power(model: Model, kin: Kinematics, per_watt: PaperEquations) -> float:
    """P from the input's load, or from the output's through η (linear in P), else 1 W."""
    p_in, p_out = _port_load(model, kin, "input"), _port_load(model, kin, "output")
    if p_in is not None and p_out is not None:
        raise StaticsError("a 1-DOF train takes one load: give the power or torque at one "
                           "port only", "ports")
    if p_in is not None:
        return p_in
    if p_out is not None:
        return p_out / per_watt.efficiency
    return 1.0


def paper_equations(model: Model, roles: RVRoles | None = None,
                    kin: Kinematics | None = None) -> PaperEquations:
    """Eqs. (8)–(15) for ``model``: β and α from its speeds, η1/η2 from its two meshes.

    Parameters
    ----------
    model : Model
        An RV-type train (not changed).
    roles, kin : optional
        Already found roles and speeds (found here when omitted).

    Returns
    -------
    PaperEquations

    Raises
    ------
    MethodNotApplicableError
        When the train is not RV-type, or the paper's power directions do not hold
        (``V > 0``, ``U > 0``, ``P > 0``).

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> eq = paper_equations(load_model("models/rv40e_wang2021.yaml"))   # doctest: +SKIP
    >>> round(eq.beta, 9), round(eq.alpha, 9)                   # doctest: +SKIP
    (39.0, 40.0)
    """
    roles = find_rv_roles(model) if roles is None else roles
    kin = solve_speeds(model) if kin is None else kin
    beta, alpha = split_ratios(kin, roles)
    eta1 = model.links[roles.first_mesh].efficiency
    eta2 = model.links[roles.cycloid_mesh].efficiency
    per_watt = PaperEquations(beta, alpha, 1.0, eta1, eta2)
    if not (beta > 1.0 and per_watt.paper_virtual_power > 0.0):
        raise _refuse(f"the paper's power directions need V > 0 and U > 0 (β = −w2/w4 > 1, "
                      f"α > β); here β = {beta:.6g}, α = {alpha:.6g}")
    power = _input_power(model, kin, per_watt)
    if not power > 0.0:
        raise _refuse(f"the paper's method describes the reducer driven at its input "
                      f"(P > 0); here P = {power:.6g} W (use the virtual-power method for "
                      "back-driving)")
    return PaperEquations(beta, alpha, float(power), eta1, eta2)


def _loaded_at_input(model: Model, roles: RVRoles, power: float) -> Model:
    """Copy with the input feeding ``power`` and no load given at the output."""
    i_in = model.inputs[0].index
    i_out = model.outputs[0].index
    return model.with_port(i_in, power=power, torque=None).with_port(i_out, power=None,
                                                                     torque=None)


def realise(model: Model, roles: RVRoles,
            eq: PaperEquations) -> tuple[PowerFlowResult, tuple[float, float]]:
    """A virtual-power solve that loses exactly L1 in mesh A and L2 in mesh B.

    The first-stage efficiency is tuned on its own loss (the input torque fixes that
    mesh's load), then the cycloid mesh's on the total loss.

    Returns
    -------
    (PowerFlowResult, (η1*, η2*))
    """
    from powergraph.methods.tuning import efficiency_for, solve_with

    base = _loaded_at_input(model, roles, eq.input_power)
    first = efficiency_for(base, roles.first_mesh,
                           lambda r: r.element(roles.first_mesh).loss, eq.first_loss)
    base = base.with_link(roles.first_mesh, efficiency=first)
    second = efficiency_for(base, roles.cycloid_mesh, lambda r: r.total_loss,
                            eq.first_loss + eq.cycloid_loss)
    return solve_with(base, roles.cycloid_mesh, second), (first, second)


def solve_wang2021(model: Model, realise_flows: bool = True) -> Wang2021Result:
    """Wang (2021)'s efficiency of an RV-type train, with the virtual-power η beside it.

    Parameters
    ----------
    model : Model
        The train (not changed). Roles are found from the graph, whatever the ids.
    realise_flows : bool
        Also build the consistent flow graph of the paper's losses (``flows``); off for
        fast sweeps.

    Returns
    -------
    Wang2021Result

    Raises
    ------
    MethodNotApplicableError
        (a ModelError: CLI exit 2) when the train is not of the RV pattern.

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> r = solve_wang2021(load_model("models/rv40e_wang2021.yaml"))       # doctest: +SKIP
    >>> eta, rigorous = r.efficiency, r.virtual_power_efficiency  # doctest: +SKIP
    >>> f"{eta:.1%} by the paper, {rigorous:.2%} rigorous"         # doctest: +SKIP
    '88.2% by the paper, 28.74% rigorous'
    """
    from powergraph.statics import solve

    places = loss_block_places(model)
    if places:
        raise MethodNotApplicableError("the paper's method takes each mesh's constant basic "
                                       "efficiency; this block derives it from friction "
                                       "(use the virtual-power method)", places[0])
    roles = find_rv_roles(model)
    kin = solve_speeds(model)
    eq = paper_equations(model, roles, kin)
    try:
        vp = solve(model)
    except SolveError:
        vp = None
    realisation, tuned = None, None
    if realise_flows:
        try:
            realisation, tuned = realise(model, roles, eq)
        except SolveError:
            pass
    return Wang2021Result(model=model, kinematics=kin, roles=roles, equations=eq,
                          virtual_power_result=vp, realisation=realisation,
                          realised_efficiencies=tuned)
