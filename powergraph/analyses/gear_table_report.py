"""The text report of a gear table (powergraph.analyses.gear_table)."""
from __future__ import annotations

from powergraph.result import aligned_table
from powergraph.statics.verdicts import MEANINGS


def gear_table_report(table) -> str:
    """One line per mode; element torques and slips below; ``-`` where a value is
    undefined (no power passes, or a zero input torque or speed to divide by). A train
    with machines, or with modes of more than one DOF or inactive ports, gets
    :func:`hybrid_report`."""
    if table.hybrid:
        return hybrid_report(table)
    rows = [["mode", "engaged", "ratio", "step", "eff %", "coast %", "drag W", "verdict"]]
    for r in table.rows:
        rows.append([r.mode, " ".join(r.engaged) + _freewheels(r), f"{r.ratio:.4f}",
                     "" if r.step is None else f"{r.step:.3f}", _percent(r.efficiency),
                     _percent(r.coast_efficiency),
                     f"{r.drag_loss:.4g}", r.verdict])
    lines = [f"{table.name} — gear table (virtual-power method)", ""]
    lines += aligned_table(rows, {2, 3, 4, 5, 6})
    spread = table.spread
    lines += ["", f"spread (forward) {spread:.4f}" if spread else "spread: no forward gear",
              "", "element torque / input torque (engaged), slip / input speed (open)"]
    names = [n for r in table.rows for n in (*r.torques, *r.slips)]
    names = list(dict.fromkeys(names))
    grid = [["mode", *names]]
    for r in table.rows:
        grid.append([r.mode, *(_cell(r, n) for n in names)])
    lines += aligned_table(grid, set(range(1, len(names) + 1)))
    coast = [f"  {r.mode}: {r.coast_verdict}" for r in table.rows
             if r.coast_verdict != "ok" and r.efficiency is not None]
    if coast:
        lines += ["", "coasting (back-driven) verdicts:", *coast]
    used = {v for r in table.rows for v in (r.verdict, r.coast_verdict)}
    legend = [f"  {v}: {MEANINGS[v]}" for v in MEANINGS if v in used]
    if legend:
        lines += ["", "verdicts:", *legend]
    lines += [f"warning: {w}" for w in table.warnings]
    return "\n".join(lines)


def _freewheels(row) -> str:
    held = [n for n, s in row.freewheels.items() if s == "holding"]
    return (" (" + " ".join(held) + ")") if held else ""


def _percent(efficiency) -> str:
    return "-" if efficiency is None else f"{100 * efficiency:.2f}"


def _cell(row, name: str) -> str:
    """``T`` torque / input torque, ``w`` slip / input speed; ``-`` when the input's is
    zero (undefined), ``indet.`` for a statically indeterminate torque."""
    if name in row.torques:
        value = row.torques[name]
        if value is None:
            return "T -" if row.input_torque is None else "indet."
        return f"T {value:.4g}"
    if name in row.slips:
        value = row.slips[name]
        return "w -" if value is None else f"w {value:.4g}"
    return ""


def hybrid_report(table) -> str:
    """Per mode its DOF, engaged elements, inactive ports, speed relation, efficiency,
    battery power, electrical share and verdict; each machine at the mode's point; the
    shift elements' torques (N·m) and slips (rpm)."""
    from powergraph.units_si import RPM_PER_RAD_S

    head = ["mode", "DOF", "engaged", "inactive", "speed relation", "eff %"]
    buses = list(dict.fromkeys(n for r in table.rows for n in r.buses))
    head += [f"{n} battery kW" for n in buses] + ["elec. %", "verdict"]
    rows = [head]
    for r in table.rows:
        rows.append([r.mode, str(r.dof), " ".join(r.engaged) + _freewheels(r) or "-",
                     " ".join(r.inactive) or "-",
                     "-" if r.relation is None else r.relation.text(),
                     _percent(r.efficiency),
                     *(_number(r.buses[n] / 1e3) if n in r.buses else "" for n in buses),
                     _percent(r.electrical_share), r.verdict])
    lines = [f"{table.name} — gear table (virtual-power method)", ""]
    lines += aligned_table(rows, {1, 5, *range(6, 7 + len(buses))})
    machines = [["mode", "machine", "state", "rpm", "torque N·m", "power kW",
                 "electrical kW"]]
    for r in table.rows:
        for m in r.machines:
            machines.append([r.mode, m.name, m.state,
                             "idle" if m.idle else _number(m.speed * RPM_PER_RAD_S),
                             _number(m.torque), _number(m.power / 1e3),
                             _number(m.electrical_power / 1e3)])
    if len(machines) > 1:
        lines += ["", "machines at each mode's point (power into the train)"]
        lines += aligned_table(machines, {3, 4, 5, 6})
    names = list(dict.fromkeys(n for r in table.rows
                               for n in (*r.element_torques, *r.slip_speeds)))
    if names:
        grid = [["mode", *names]]
        for r in table.rows:
            grid.append([r.mode, *(_absolute(r, n, RPM_PER_RAD_S) for n in names)])
        lines += ["", "shift elements: torque N·m (engaged), slip rpm (open)"]
        lines += aligned_table(grid, set(range(1, len(names) + 1)))
    used = {r.verdict for r in table.rows}
    legend = [f"  {v}: {MEANINGS[v]}" for v in MEANINGS if v in used]
    if legend:
        lines += ["", "verdicts:", *legend]
    lines += [f"warning: {w}" for w in table.warnings]
    return "\n".join(lines)


def _number(value: float) -> str:
    return f"{value + 0.0:.4g}"


def _absolute(row, name: str, rpm: float) -> str:
    """``T`` an engaged element's torque (N·m), ``w`` an open one's slip (rpm); ``w idle``
    beside an idle member, ``indet.`` for a statically indeterminate torque."""
    if name in row.element_torques:
        value = row.element_torques[name]
        return "indet." if value is None else f"T {value + 0.0:.4g}"
    if name in row.slip_speeds:
        value = row.slip_speeds[name]
        return "w idle" if value is None else f"w {value * rpm + 0.0:.4g}"
    return ""
