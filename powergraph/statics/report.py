"""The JSON object and the readable text report of ``powergraph solve`` (docs/format.md).

Works on the result it is given: it never imports :mod:`powergraph.statics.result`, whose
methods import this module (the annotations name the type as text).
"""
from __future__ import annotations

import math
import textwrap
from typing import Any

from powergraph.format import column, power_unit, ratio_text, table
from powergraph.statics.loss_sources import losses
from powergraph.statics.machine_report import boundary_powers, machine_dict, machine_lines
from powergraph.statics.verdicts import verdict_of
from powergraph.units_si import RPM_PER_RAD_S


def result_to_dict(result: PowerFlowResult) -> dict[str, Any]:
    """The keys of ``solve --json`` (docs/format.md), plus ``passes``,
    ``load_sharing_assumed``, ``lock`` (null, or why the train cannot move as asked:
    docs/locking.md) and ``directions`` (null, or how the search found the directions
    when the fixed-point iteration cycled), ``ports`` (each port's speed, torque and power,
    positive into the train), ``formal_efficiency``, ``efficiency_note``,
    ``loss_breakdown`` (where the power goes) and ``warnings``.

    Component ids in lists (``between``, ``carrier``, ``driver``) are written as in the
    model file; dictionary keys are their string forms.
    """
    model = result.model
    raw = model.raw_id
    meshes = [{"link": e.link, "between": [raw(e.a), raw(e.b)], "carrier": raw(e.carrier),
               "driver": raw(e.driver) if e.driver is not None else None,
               "virtual_power": e.carrier_frame_power, "loss": e.loss, "efficiency": e.efficiency,
               "willis_ratio": e.ratio}
              for e in result.meshes]
    return {
        "name": model.name,
        "method": result.method,
        "dof": result.dof,
        "ratio": result.ratio,
        "efficiency": result.efficiency,
        "input_power": result.input_power,
        "output_power": result.output_power,
        "total_loss": result.total_loss,
        "speeds": {c: None if c in model.idle else w for c, w in result.speeds.items()},
        "torques": result.torques,
        "meshes": meshes,
        "flows": [f.to_dict() for f in result.flows()],
        "circulating_power": result.circulating_power,
        "self_locking": result.self_locking,
        "verdict": verdict_of(result),
        "formal_efficiency": _finite(result.formal_efficiency),
        "efficiency_note": result.efficiency_note,
        "ports": [p.to_dict(raw) for p in result.ports],
        "loss_breakdown": [{"source": source, "power": loss}
                           for source, loss in loss_sources(result)],
        "warnings": [str(caveat) for caveat in result.warnings],
        "passes": result.passes,
        "load_sharing_assumed": result.load_sharing_assumed,
        **_friction_dict(result),
        **_oil_dict(result),
        **machine_dict(result),
        "lock": result.lock.to_dict() if result.lock is not None else None,
        "directions": result.search.to_dict() if result.search is not None else None,
    }


def _friction_dict(result: PowerFlowResult) -> dict[str, Any]:
    out: dict[str, Any] = {}
    if result.friction:
        out["friction"] = [state.to_dict() for state in result.friction]
    if result.bearings:
        out["bearings"] = [state.to_dict(result.model) for state in result.bearings]
        out["bearing_loss"] = result.bearing_loss
    if out:
        out["friction_passes"] = result.friction_passes
    return out


def _oil_dict(result: PowerFlowResult) -> dict[str, Any]:
    """``lubricant``, ``thermal`` and ``no_load_torque``, where they apply."""
    out: dict[str, Any] = {}
    if result.model.lubricant is not None:
        out["lubricant"] = result.model.lubricant.to_dict()
    if result.thermal is not None:
        out["thermal"] = result.thermal.to_dict()
    torque = no_load_torque(result)
    if torque is not None:
        out["no_load_torque"] = torque
    return out


def no_load_torque(result: PowerFlowResult) -> float | None:
    """The input torque (N·m) that keeps the train turning when nothing is taken at the
    outputs (power enters at its one input and none leaves at the outputs): a catalogue's
    no-load running torque; None otherwise."""
    model = result.model
    if len(model.inputs) != 1 or result.machines or not result.input_power > 0.0:
        return None
    if any(abs(p.power) > 1e-12 * result.input_power for p in result.ports
           if p.role == "output"):
        return None
    return result.torques[model.inputs[0].component]


def _finite(value: float) -> float | None:
    return value if math.isfinite(value) else None


def loss_sources(result: PowerFlowResult) -> list[tuple[str, float]]:
    """Where the power goes: each loss source of the model
    (:func:`powergraph.statics.loss_sources.losses`: meshes, a cycloid mesh split into its
    pins, output pins and crank bearings, lossy couplings, bearings and drags, machines,
    any registered kind) as ``(label, W)``; they sum to the total loss.

    A cycloid mesh's basic efficiency is the product of its parts' (docs/losses.md); its
    loss is shared among them in proportion to ``-ln η`` of each, which adds up exactly.
    """
    model = result.model
    out = []
    for source, loss in losses(result):
        if source.applied == "machine":
            out.append((f"{source.label} (component {model.raw_id(source.between[0])})", loss))
        elif source.applied == "element":
            name = getattr(model.links[source.link], "name", None)
            label = f"{source.node} ({_names(model, source.between, name)})"
            out += _split(label, loss, getattr(source.friction, "loss", None))
        else:
            prefix = f"links[{source.link}] " if source.link is not None else ""
            drag = " drag" if source.kind == "drag" and "drag" not in source.node else ""
            out.append((f"{prefix}{source.node} ({_names(model, source.between, None)}){drag}",
                        loss))
    return out


def _names(model, ids, name: str | None) -> str:
    """``center gear / planet gear`` (or the link's own name)."""
    if name:
        return name
    return " / ".join(model.components[c].name or str(model.raw_id(c)) for c in ids)


def _split(label: str, loss: float, stage) -> list[tuple[str, float]]:
    parts = []
    if hasattr(stage, "pin_efficiency"):     # a cycloid stage (CycloidLoss)
        parts = [(name, eta) for name, eta in (("pins", stage.pin_efficiency),
                                               ("output pins", stage.output_efficiency),
                                               ("crank bearings", stage.bearing_efficiency))
                 if eta < 1.0]
    weights = [-math.log(eta) for _, eta in parts]
    if len(parts) < 2 or not all(w > 0 for w in weights):
        return [(label, loss)]
    total = sum(weights)
    return [(f"{label}: {name}", loss * w / total) for (name, _), w in zip(parts, weights)]


def _verdict_lines(result: PowerFlowResult) -> list[str]:
    """LOCKED (with the meshes and why), SELF-LOCKING, or the search's finding."""
    lock, search = result.lock, result.search
    if lock is not None:
        lines = ["LOCKED: the train cannot move as asked under these loads; it stays at rest",
                 "  (every mesh sticks; the torques shown are the lossless holding torques,",
                 "  one of the set static friction can hold: docs/locking.md)"]
        if lock.meshes:
            lines.append("  locking " + ("mesh" if len(lock.meshes) == 1 else "meshes") + ": "
                         + ", ".join(f"links[{k}]" for k in lock.meshes))
        lines += [f"  - {reason}" for reason in lock.reasons]
        return lines
    lines = []
    if result.self_locking:
        lines.append("SELF-LOCKING: the input cannot drive the output in this direction "
                     "(the output must be driven too)")
    if search is not None and search.solutions > 1:
        lines.append(f"several consistent power-direction patterns ({search.solutions}"
                     f"{'' if search.complete else '+'}): the one of least total loss is shown")
    return lines


def summary_line(result: PowerFlowResult) -> str:
    """``RV-40E, 1 DOF, ratio 121 : 1, efficiency 87.02 %`` (``repr`` of a result)."""
    parts = [result.name, f"{result.dof} DOF"]
    if result.ratio is not None:
        parts.append(f"ratio {ratio_text(result.ratio)}")
    parts.append(f"efficiency {_percent(result.efficiency)}")
    return ", ".join(parts)


def html_summary(result: PowerFlowResult) -> str:
    """A small HTML table (notebooks): summary rows, then the ports."""
    from html import escape

    rows = [("train", result.name), ("DOF", str(result.dof))]
    if result.ratio is not None:
        rows.append(("ratio", ratio_text(result.ratio)))
    rows += [("efficiency", _percent(result.efficiency)),
             ("losses", _power(result.total_loss))]
    body = "".join(f"<tr><th style='text-align:left'>{escape(k)}</th><td>{escape(v)}</td>"
                   f"<td colspan='4'></td></tr>" for k, v in rows)
    head = "".join(f"<th>{h}</th>" for h in ("port", "role", "rpm", "torque N·m", "power W",
                                              "direction"))
    ports = "".join(
        "<tr>" + "".join(f"<td>{escape(c)}</td>" for c in (
            _port_label(result, p), p.role, f"{p.speed * RPM_PER_RAD_S:.6g}", f"{p.torque + 0.0:.6g}",
            f"{p.power + 0.0:.6g}", p.direction)) + "</tr>" for p in result.ports)
    warnings = "".join(f"<p>warning: {escape(str(w))}</p>" for w in result.warnings)
    return (f"<table>{body}<tr>{head}</tr>{ports}</table>{warnings}")


def _percent(eta: float | None) -> str:
    return "undefined (no power passes)" if eta is None else f"{eta * 100:.2f} %"


def _power(watts: float) -> str:
    unit, scale = power_unit([watts])
    return f"{column([watts], scale)[0]} {unit}"


def _port_label(result: PowerFlowResult, port) -> str:
    label = result.model.components[port.component].label
    return f"{port.name} ({label})" if port.name else label


def text_report(result: PowerFlowResult) -> str:
    """A readable report: summary, warnings, ports, speeds, torques, meshes, losses."""
    model = result.model
    lines = [f"{model.name} — virtual-power method ({result.dof} DOF)"]
    if model.description:
        lines.append(textwrap.fill(" ".join(model.description.split()), width=88,
                                   initial_indent="  ", subsequent_indent="  "))
    lines += [""] + _summary_lines(result)
    lines += [f"warning: {caveat}" for caveat in result.warnings]
    lines += _verdict_lines(result)
    lines += ["", "ports (torque on the train, power positive into the train)"]
    lines += _ports_table(result)
    lines += ["", "speeds"] + _speeds_table(result)
    lines += ["", "meshes (powers in each mesh's carrier frame)"] + _mesh_table(result)
    lines += _friction_lines(result)
    lines += _bearing_lines(result)
    lines += machine_lines(result)
    lines += ["", "where the power goes"] + _losses_table(result)
    if result.load_sharing_assumed:
        lines += ["", "note: load sharing between parallel paths is statically indeterminate; "
                  "the minimum-norm (equal) sharing was assumed"]
    return "\n".join(lines)


def _summary_lines(result: PowerFlowResult) -> list[str]:
    crossing = boundary_powers(result)
    entering = sum(p for p in crossing if p > 0)
    leaving = -sum(p for p in crossing if p < 0)
    unit, scale = power_unit([entering, leaving, result.total_loss])
    powers = column([entering, leaving, result.total_loss], scale)
    rows = []
    if result.ratio is not None:
        rows.append(["ratio (input : output speed)", ratio_text(result.ratio)])
    rows += [["power in (at the ports)", f"{powers[0]} {unit}"],
             ["power out (at the ports)", f"{powers[1]} {unit}"],
             ["losses", f"{powers[2]} {unit}"],
             ["efficiency (out / in)", _percent(result.efficiency)
              if result.efficiency is not None else f"undefined: {result.efficiency_note}"]]
    formal = result.formal_efficiency
    if result.efficiency is not None and result.lock is None and math.isfinite(formal) \
            and abs(formal - result.efficiency) > 1e-9:
        rows.append(["formal efficiency", f"{formal * 100:.2f} % (declared output / "
                                          "declared input)"])
    if result.circulating_power > 0:
        rows.append(["circulating power", _power(result.circulating_power)])
    return table(rows + _oil_rows(result), set(), indent="")


def _oil_rows(result: PowerFlowResult) -> list[list[str]]:
    """The oil's temperature and viscosity, the heat balance, the no-load torque."""
    rows = []
    oil = result.model.lubricant
    if oil is not None:
        verdict = None if result.thermal is None else result.thermal.verdict
        how = {None: "given", "ok": "from the heat balance"}.get(verdict, verdict)
        rows.append(["oil", f"{oil.temperature - 273.15:.1f} degC ({how}), "
                            f"{oil.viscosity() * 1e6:.4g} cSt, {oil.density:g} kg/m^3"])
    if result.thermal is not None:
        rows.append(["heat given off", f"{_power(result.thermal.heat_dissipated)} "
                                       f"(ambient {result.thermal.ambient - 273.15:.1f} degC)"])
    torque = no_load_torque(result)
    if torque is not None:
        rows.append(["no-load running torque", f"{torque:.6g} N·m at the input"])
    return rows


def _ports_table(result: PowerFlowResult) -> list[str]:
    ports = result.ports
    unit, scale = power_unit([p.power for p in ports])
    rpm = column([p.speed * RPM_PER_RAD_S for p in ports])
    torque = column([p.torque for p in ports])
    power = column([p.power for p in ports], scale)
    rows = [["port", "name", "component", "role", "rpm", "torque N·m", f"power {unit}",
             "direction"]]
    model = result.model
    for k, p in enumerate(ports):
        rows.append([p.path, p.name or "", model.components[p.component].label,
                     p.role, "idle" if p.component in model.idle else rpm[k], torque[k],
                     power[k], "inactive" if p.index in model.inactive else
                     {"in": "enters", "out": "leaves", "none": "none"}[p.direction]])
    return table(rows, {4, 5, 6})


def _speeds_table(result: PowerFlowResult) -> list[str]:
    speeds = result.speeds
    ids = list(speeds)
    rad = column([speeds[c] for c in ids])
    rpm = column([speeds[c] * RPM_PER_RAD_S for c in ids])
    torques = result.torques
    torque = column([torques.get(c, 0.0) for c in ids])
    rows = [["component", "rad/s", "rpm", "external torque N·m"]]
    idle = result.model.idle
    for k, c in enumerate(ids):
        rows.append([result.model.components[c].label,
                     *(("idle", "idle") if c in idle else (rad[k], rpm[k])),
                     torque[k] if c in torques else ""])
    return table(rows, {1, 2, 3})


def _mesh_table(result: PowerFlowResult) -> list[str]:
    meshes = result.meshes
    if not meshes:
        return ["  (none)"]
    raw = result.model.raw_id
    unit, scale = power_unit([e.carrier_frame_power for e in meshes])
    virtual = column([e.carrier_frame_power for e in meshes], scale)
    loss_unit, loss_scale = power_unit([e.loss for e in meshes])
    loss = column([e.loss for e in meshes], loss_scale)
    rows = [["link", "between", "carrier", "eta", "driver", f"virtual power {unit}",
             f"loss {loss_unit}"]]
    for k, e in enumerate(meshes):
        name = getattr(result.model.links[e.link], "name", None)
        rows.append([f"{e.link}" + (f" ({name})" if name else ""), f"{raw(e.a)}-{raw(e.b)}",
                     str(raw(e.carrier)), f"{e.efficiency:.6g}",
                     str(raw(e.driver)) if e.driver is not None else "-", virtual[k], loss[k]])
    return table(rows, {3, 4, 5, 6})


def _losses_table(result: PowerFlowResult) -> list[str]:
    sources = loss_sources(result)
    if not sources:
        return ["  (no losses)"]
    entering = sum(p.power for p in result.ports if p.power > 0)
    values = [loss for _, loss in sources] + [result.total_loss]
    unit, scale = power_unit(values)
    shown = column(values, scale)
    share = column([100 * v / entering if entering else float("nan") for v in values],
                   significant=3)
    rows = [["source", f"loss {unit}", "% of power in"]]
    rows += [[label, shown[k], share[k]] for k, (label, _) in enumerate(sources)]
    rows.append(["total", shown[-1], share[-1]])
    return table(rows, {1, 2})


def _friction_lines(result: PowerFlowResult) -> list[str]:
    if not result.friction:
        return []
    passes = (f", {result.friction_passes} passes" if result.friction_passes > 1 else "")
    rows = [["link", "model", "F_t N", "v_t m/s", "mu", "H_V", "eta"]]
    for s in result.friction:
        rows.append([str(s.link), s.model, f"{s.tangential_force:.5g}",
                     f"{s.pitch_speed:.4g}", f"{s.mu:.4g}", f"{s.loss_factor:.4g}",
                     f"{s.efficiency:.6f}"])
    return (["", f"mesh friction (per mesh instance, carrier frame{passes})"]
            + table(rows, {2, 3, 4, 5, 6}))


def _bearing_lines(result: PowerFlowResult) -> list[str]:
    if not result.bearings:
        return []
    raw = result.model.raw_id
    bearings = result.bearings
    unit, scale = power_unit([b.loss for b in bearings])
    loss = column([b.loss for b in bearings], scale)
    rows = [["node", "between", "n rel rpm", "F N", "M_mu N·m", "M0 N·m", "M N·m",
             f"loss {unit}"]]
    for k, b in enumerate(bearings):
        rows.append([b.node, f"{raw(b.between[0])}-{raw(b.between[1])}",
                     _g(b.relative_speed * RPM_PER_RAD_S, 5), _g(b.radial_load, 5),
                     _g(b.friction_torque, 4), _g(b.drag_torque, 4), _g(b.torque, 4), loss[k]])
    return (["", "bearings and drag (F, friction and drag torques per instance; M the total)"]
            + table(rows, {2, 3, 4, 5, 6, 7}))


def _g(value: float, digits: int) -> str:
    """``value`` to ``digits`` significant digits, never ``-0``."""
    return f"{value + 0.0:.{digits}g}".replace("-0e", "0e") if value != 0 else "0"
