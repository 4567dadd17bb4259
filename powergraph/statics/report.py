"""The JSON object and the readable text report of ``powergraph solve`` (docs/format.md)."""
from __future__ import annotations

from typing import Any

from powergraph.statics.result import PowerFlowResult
from powergraph.units_si import RPM_PER_RAD_S


def result_to_dict(result: PowerFlowResult) -> dict[str, Any]:
    """The keys of ``solve --json`` (docs/format.md), plus ``passes``,
    ``load_sharing_assumed``, ``lock`` (null, or why the train cannot move as asked:
    docs/locking.md) and ``directions`` (null, or how the search found the directions
    when the fixed-point iteration cycled).

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
        "speeds": result.speeds,
        "torques": result.torques,
        "meshes": meshes,
        "flows": [f.to_dict() for f in result.flows()],
        "circulating_power": result.circulating_power,
        "self_locking": result.self_locking,
        "passes": result.passes,
        "load_sharing_assumed": result.load_sharing_assumed,
        **_friction_dict(result),
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


def _fmt_power(watts: float) -> str:
    return f"{watts / 1000:,.4f} kW" if abs(watts) >= 1000 else f"{watts:,.4f} W"


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


def text_report(result: PowerFlowResult) -> str:
    """A readable report: speeds (rpm), external torques, per-mesh table, efficiency."""
    model = result.model
    lines = [f"{model.name} — virtual-power method ({result.dof} DOF)"]
    if model.description:
        lines.append(f"  {model.description.strip()}")
    lines.append("")
    if result.ratio is not None:
        lines.append(f"ratio (input/output speed)  {result.ratio:.6g}")
    lines += [f"input power                 {_fmt_power(result.input_power)}",
              f"output power                {_fmt_power(result.output_power)}",
              f"losses                      {_fmt_power(result.total_loss)}",
              f"efficiency                  {result.efficiency * 100:.4f} %"]
    lines += _verdict_lines(result)
    if result.circulating_power > 0:
        lines.append(f"circulating power           {_fmt_power(result.circulating_power)}")
    lines += ["", "speeds", f"  {'component':<24}{'rad/s':>14}{'rpm':>14}"]
    for cid, w in result.speeds.items():
        lines.append(f"  {model.components[cid].label:<24}{w:>14.6g}{w * RPM_PER_RAD_S:>14.6g}")
    lines += ["", "external torques (N·m, positive in the sense of positive speed)"]
    for cid, t in result.torques.items():
        lines.append(f"  {model.components[cid].label:<24}{t:>14.6g}")
    lines += ["", "meshes (powers in each mesh's carrier frame)",
              f"  {'link':<6}{'between':<10}{'carrier':<9}{'eta':>7}{'driver':>8}"
              f"{'virtual power':>18}{'loss':>14}"]
    raw = model.raw_id
    for e in result.meshes:
        driver = str(raw(e.driver)) if e.driver is not None else "-"
        lines.append(f"  {e.link:<6}{f'{raw(e.a)}-{raw(e.b)}':<10}{str(raw(e.carrier)):<9}"
                     f"{e.efficiency:>7.4g}{driver:>8}{_fmt_power(e.carrier_frame_power):>18}"
                     f"{_fmt_power(e.loss):>14}")
    lines += _friction_lines(result)
    lines += _bearing_lines(result)
    if result.load_sharing_assumed:
        lines += ["", "note: load sharing between parallel paths is statically indeterminate; "
                  "the minimum-norm (equal) sharing was assumed"]
    return "\n".join(lines)


def _friction_lines(result: PowerFlowResult) -> list[str]:
    if not result.friction:
        return []
    passes = (f", {result.friction_passes} passes" if result.friction_passes > 1 else "")
    lines = ["", f"mesh friction (per mesh instance, carrier frame{passes})",
             f"  {'link':<6}{'model':<10}{'F_t N':>12}{'v_t m/s':>10}{'mu':>9}{'H_V':>9}"
             f"{'eta':>10}"]
    for s in result.friction:
        lines.append(f"  {s.link:<6}{s.model:<10}{s.tangential_force:>12.5g}"
                     f"{s.pitch_speed:>10.4g}{s.mu:>9.4g}{s.loss_factor:>9.4g}"
                     f"{s.efficiency:>10.6f}")
    return lines


def _bearing_lines(result: PowerFlowResult) -> list[str]:
    if not result.bearings:
        return []
    raw = result.model.raw_id
    lines = ["", "bearings and drag (F, friction and drag torques per instance; M the total)",
             f"  {'node':<16}{'between':<10}{'n rel rpm':>11}{'F N':>11}{'M_mu N·m':>11}"
             f"{'M0 N·m':>10}{'M N·m':>10}{'loss':>14}"]
    for b in result.bearings:
        between = f"{raw(b.between[0])}-{raw(b.between[1])}"
        lines.append(f"  {b.node:<16}{between:<10}{b.relative_speed * RPM_PER_RAD_S:>11.5g}"
                     f"{b.radial_load:>11.5g}{b.friction_torque:>11.4g}{b.drag_torque:>10.4g}"
                     f"{b.torque:>10.4g}{_fmt_power(b.loss):>14}")
    return lines
