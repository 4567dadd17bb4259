"""Text and CSV views of a :class:`~powergraph.analyses.cycle.CycleResult`."""
from __future__ import annotations

import csv
import io
from typing import TYPE_CHECKING, Any

from powergraph.format import aligned_table, format_number

if TYPE_CHECKING:   # pragma: no cover
    from powergraph.analyses.cycle import CycleResult

#: CSV columns of the per-row results, with their units.
COLUMNS = (("row", None), ("duration", "s"), ("mode", None), ("power_in", "W"),
           ("power_out", "W"), ("loss", "W"), ("efficiency", "-"), ("verdict", None),
           ("electrical_share", "-"), ("negative_split", None), ("warnings", None))


def text_report(result: "CycleResult") -> str:
    """Totals first (energies in kJ), then the energy lost per element."""
    kj = lambda joules: format_number(joules / 1e3, 6)   # noqa: E731
    eff = result.efficiency
    lines = [f"{result.name} — duty cycle, {len(result.rows)} operating points "
             f"({result.method})", "",
             f"time                {format_number(sum(r.duration for r in result.rows), 6)} s",
             f"energy in           {kj(result.energy_in)} kJ",
             f"energy out          {kj(result.energy_out)} kJ",
             f"energy lost         {kj(sum(result.energy_lost.values()))} kJ",
             "cycle efficiency    " + (f"{eff:.2%}" if eff is not None else
                                       "undefined (no energy enters)")]
    if any(r.negative_split is not None for r in result.rows):
        lines.append(f"negative split      {format_number(result.negative_split_time, 6)} s "
                     "(power circulating through a bus)")
    if result.locked_rows:
        lines.append(f"rows that lock      {', '.join(str(i + 2) for i in result.locked_rows)}"
                     " (file lines)")
    for code, rows in result.warned_rows.items():
        shown = ", ".join(str(i + 2) for i in rows[:12]) + (", …" if len(rows) > 12 else "")
        lines.append(f"warning: {code} in {len(rows)} row(s), file lines {shown} "
                     "(solve one for the details)")
    errors = [r for r in result.rows if r.verdict.startswith("error")]
    lines += [f"warning: row {r.index + 2}: {r.verdict[7:]}" for r in errors]
    modes = result.time_per_mode
    if list(modes) != ["-"]:
        lines += ["", "time per mode"]
        lines += aligned_table([["mode", "time [s]"]] + [[m, format_number(t, 6)]
                                                         for m, t in modes.items()], {1})
    lost = result.energy_lost
    if lost:
        lines += ["", "energy lost per element"]
        lines += aligned_table([["element", "energy [kJ]"]]
                               + [[label, kj(j)] for label, j in lost.items()], {1})
    return "\n".join(lines)


def to_csv(result: "CycleResult", path: Any = None) -> str | None:
    """The per-row results as CSV (units in the header); written to ``path``, or
    returned as text when ``path`` is None."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow([f"{name} [{unit}]" if unit else name for name, unit in COLUMNS])
    for r in result.rows:
        writer.writerow([r.index, repr(r.duration), r.mode or "", repr(r.power_in),
                         repr(r.power_out), repr(r.loss),
                         "" if r.efficiency is None else repr(r.efficiency), r.verdict,
                         "" if r.electrical_share is None else repr(r.electrical_share),
                         "" if r.negative_split is None else str(r.negative_split).lower(),
                         ";".join(r.warnings)])
    if path is None:
        return out.getvalue()
    with open(path, "w", encoding="utf-8", newline="") as f:
        f.write(out.getvalue())
    return None
