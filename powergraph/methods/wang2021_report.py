"""JSON object, readable report and the paper's Fig. 5 graph of a :class:`Wang2021Result`.

Component ids in lists are written as in the model file (``model.raw_id``); dictionary
keys are their string forms, as in the virtual-power report (docs/format.md). Works on
the result it is given: it never imports :mod:`powergraph.methods.wang2021`, whose result
calls these functions (the annotations name the type as text).

Examples
--------
>>> from powergraph.model import load_model
>>> from powergraph.methods.wang2021 import solve_wang2021
>>> result = solve_wang2021(load_model("models/rv40e_wang2021.yaml"))     # doctest: +SKIP
>>> data = result_to_dict(result)                                # doctest: +SKIP
>>> data["method"], [round(x, 2) for x in data["losses"]]        # doctest: +SKIP
('wang2021', [136.2, 131.52])
>>> [(f.source, f.target) for f in split_flows(result)][3]       # doctest: +SKIP
('2/3', '6/7')
>>> "88.2062 %" in text_report(result)                           # doctest: +SKIP
True
"""
from __future__ import annotations

from typing import Any

from powergraph.format import format_ratio
from powergraph.methods.tuning import lossless_cycloid_power
from powergraph.statics.flow import BODY, GENERATOR, MOTOR, Flow
from powergraph.units_si import RPM_PER_RAD_S


def _pair(result: "Wang2021Result", link: int) -> str:
    """``1-2``: the link's two components as written in the file."""
    a, b = (result.model.raw_id(c) for c in result.model.links[link].between)
    return f"{a}-{b}"


def _node(result: "Wang2021Result", link: int) -> str:
    """Element node name as the core flow graph writes it (``mesh 1-2``)."""
    return f"{result.model.links[link].type} {_pair(result, link)}"


def split_flows(result: "Wang2021Result") -> list[Flow]:
    """The paper's Fig. 5 (no losses): P in, split at the planet/crank body into V to the
    output body and P − V through the cycloid; P out."""
    roles, p, v = result.roles, result.input_power, result.split_power
    model = result.model
    first, cycloid, coupling = (_node(result, i) for i in
                                (roles.first_mesh, roles.cycloid_mesh, roles.coupling))
    first_k, cycloid_k, coupling_k = (model.links[i].type for i in
                                      (roles.first_mesh, roles.cycloid_mesh, roles.coupling))
    input_body = model.body_of[roles.input_gear]
    cycloid_body = model.body_of[roles.cycloid]
    planet, output = roles.planet_body, roles.output_body
    return [Flow(MOTOR, input_body, p, MOTOR, BODY), Flow(input_body, first, p, BODY, first_k),
            Flow(first, planet, p, first_k, BODY), Flow(planet, output, v),
            Flow(planet, cycloid, p - v, BODY, cycloid_k),
            Flow(cycloid, cycloid_body, p - v, cycloid_k, BODY),
            Flow(cycloid_body, coupling, p - v, BODY, coupling_k),
            Flow(coupling, output, p - v, coupling_k, BODY),
            Flow(output, GENERATOR, p, BODY, GENERATOR)]


def _meshes(result: "Wang2021Result") -> list[dict[str, Any]]:
    raw = result.model.raw_id
    return [{"link": m.link, "role": m.role, "between": [raw(m.a), raw(m.b)],
             "carrier": raw(m.carrier), "driver": raw(m.driver), "efficiency": m.efficiency,
             "virtual_power": m.applied_power, "loss": m.loss} for m in result.meshes]


def result_to_dict(result: "Wang2021Result") -> dict[str, Any]:
    """The ``solve --json`` keys with the paper's numbers, then ``split_power`` (V),
    ``virtual_power`` (the paper's U), ``losses`` ([L1, L2]), ``beta``, ``alpha``, and:
    ``roles``, ``equations`` (the paper's equation per quantity),
    ``virtual_power_efficiency`` (rigorous η, same file), ``split_flows`` (Fig. 5) and
    ``realised_efficiencies`` (the tuned basic efficiencies behind ``flows``). Per mesh,
    ``virtual_power`` is the power the paper applies the mesh's efficiency to."""
    model = result.model
    tuned = result.realised_efficiencies
    return {
        "name": model.name, "method": result.method, "dof": result.dof,
        "ratio": result.ratio, "efficiency": result.efficiency,
        "input_power": result.input_power, "output_power": result.output_power,
        "total_loss": result.total_loss, "speeds": result.speeds, "torques": result.torques,
        "meshes": _meshes(result), "flows": [f.to_dict() for f in result.flows()],
        "circulating_power": result.circulating_power, "self_locking": result.self_locking,
        "warnings": [str(caveat) for caveat in model.warnings],
        "split_power": result.split_power, "virtual_power": result.paper_virtual_power,
        "losses": list(result.losses), "beta": result.beta, "alpha": result.alpha,
        "roles": result.roles.to_dict(model),
        "equations": {"beta": "Eq. 8: -w2/w4", "alpha": "Eq. 12: (w4 - w3)/w4",
                      "split_power": "Eqs. 8-9: P (1 - 1/beta)",
                      "virtual_power": "Eq. 12: alpha (P - V) - P",
                      "losses": "Eq. 13: P (1 - eta1); Eq. 14: (P + U - L1)(1 - eta2)",
                      "efficiency": "Eq. 15: (P - L1 - L2)/P"},
        "virtual_power_efficiency": result.virtual_power_efficiency,
        "split_flows": [f.to_dict() for f in result.split_flows()],
        "realised_efficiencies": list(tuned) if tuned is not None else None,
    }


def _power(watts: float) -> str:
    return f"{watts:,.4f} W"


def _roles_line(result: "Wang2021Result") -> str:
    r, raw = result.roles, result.model.raw_id
    return (f"  roles: input central gear {raw(r.input_gear)}; planet/crank body "
            f"{r.planet_body} (planet of mesh {_pair(result, r.first_mesh)}, carrier of "
            f"mesh {_pair(result, r.cycloid_mesh)}); cycloid {raw(r.cycloid)} coupled to "
            f"output body {r.output_body}; pin gear {raw(r.pin_gear)} fixed")


def _why(result: "Wang2021Result") -> list[str]:
    vp = result.virtual_power_result
    if vp is None:
        return ["virtual-power method: no consistent solution (see `powergraph solve`)"]
    passed = lossless_cycloid_power(result.model, result.roles.cycloid_mesh)
    eq = result.equations
    return [f"virtual-power method, same file   {vp.efficiency * 100:.4f} %",
            "  why they differ: Eq. (14) applies eta2 to P + U - L1 = "
            f"{eq.cycloid_power / eq.input_power:.3g} x P,",
            "  but in the crank's frame, where a basic efficiency belongs, the cycloid-pin",
            f"  mesh passes {passed / eq.input_power:.3g} x P (ideal meshes)."]


def text_report(result: "Wang2021Result") -> str:
    """Readable report: roles, β, α, V, U, L1, L2, η with their equations, then the
    virtual-power η of the same file and one sentence on why they differ."""
    eq, model = result.equations, result.model
    lines = [f"{model.name} — Wang (2021) split/virtual power method", _roles_line(result), ""]
    if result.ratio is not None:
        lines.append(f"ratio (input/output speed)        {format_ratio(result.ratio, 6)}")
    lines += [f"split power ratio beta = -w2/w4   {eq.beta:.6g}    (Eq. 8)",
              f"virtual power ratio alpha         {eq.alpha:.6g}    (Eq. 12)",
              f"input power P                     {_power(eq.input_power)}",
              f"split power V                     {_power(eq.split_power)}    (Eq. 9)",
              f"virtual power U                   {_power(eq.paper_virtual_power)}    (Eq. 12)",
              f"mesh efficiencies eta1, eta2      {eq.eta1:.6g}, {eq.eta2:.6g}",
              f"L1 = P(1 - eta1)                  {_power(eq.first_loss)}    (Eq. 13)",
              f"L2 = (P + U - L1)(1 - eta2)       {_power(eq.cycloid_loss)}    (Eq. 14)",
              f"output power                      {_power(result.output_power)}",
              f"efficiency                        {eq.efficiency * 100:.4f} %    (Eq. 15)", ""]
    lines += _why(result)
    lines += ["", "speeds", f"  {'component':<24}{'rad/s':>14}{'rpm':>14}"]
    for cid, w in result.speeds.items():
        lines.append(f"  {model.components[cid].label:<24}{w:>14.6g}{w * RPM_PER_RAD_S:>14.6g}")
    lines += ["", "external torques consistent with the paper's efficiency (N·m)"]
    for cid, t in result.torques.items():
        lines.append(f"  {model.components[cid].label:<24}{t:>14.6g}")
    return "\n".join(lines)
