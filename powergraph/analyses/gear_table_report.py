"""The text report of a gear table (powergraph.analyses.gear_table)."""
from __future__ import annotations

from powergraph.result import aligned_table
from powergraph.statics.verdicts import MEANINGS


def gear_table_report(table) -> str:
    """One line per mode; element torques and slips below; ``-`` where a value is
    undefined (no power passes, or a zero input torque or speed to divide by)."""
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
