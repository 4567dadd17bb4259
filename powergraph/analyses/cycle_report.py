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


#: Rows named one by one in the text report, per list.
SHOWN = 12


def text_report(result: "CycleResult") -> str:
    """Totals first (energies in kJ), then the energy lost per element. The totals are
    over the rows solved; the rows left out (``keep_going``) are counted and named."""
    kj = lambda joules: format_number(joules / 1e3, 6)   # noqa: E731
    eff = result.efficiency
    lines = [f"{result.name} — duty cycle, {len(result.rows)} operating points "
             f"({result.method})", "",
             f"time                {format_number(result.time, 6)} s",
             f"energy in           {kj(result.energy_in)} kJ",
             f"energy out          {kj(result.energy_out)} kJ",
             f"energy lost         {kj(sum(result.energy_lost.values()))} kJ",
             "cycle efficiency    " + (f"{eff:.2%}" if eff is not None else
                                       "undefined (no energy enters)")]
    left_out = [result.rows[i] for i in result.left_out]
    if left_out:
        lines.append(f"left out            {len(left_out)} row(s), "
                     f"{format_number(result.left_out_time, 6)} s (cannot be solved; file "
                     f"lines {_shown([r.file_line for r in left_out])})")
    if any(r.negative_split is not None for r in result.rows):
        lines.append(f"negative split      {format_number(result.negative_split_time, 6)} s "
                     "(power circulating through a bus)")
    if result.locked_rows:
        lines.append(f"rows that lock      {_shown(_lines(result, result.locked_rows))}"
                     " (file lines)")
    for code, rows in result.warned_rows.items():
        lines.append(f"warning: {code} in {len(rows)} row(s), file lines "
                     f"{_shown(_lines(result, rows))} (solve one for the details)")
    lines += [f"warning: row {r.file_line}: {r.verdict[7:]}" for r in left_out[:SHOWN]]
    if len(left_out) > SHOWN:
        lines.append(f"warning: {len(left_out) - SHOWN} more row(s) cannot be solved "
                     "(their verdicts: --json or -o)")
    modes = result.time_per_mode
    if modes and list(modes) != ["-"]:
        lines += ["", "time per mode"]
        lines += aligned_table([["mode", "time [s]"]] + [[m, format_number(t, 6)]
                                                         for m, t in modes.items()], {1})
    lost = result.energy_lost
    if lost:
        lines += ["", "energy lost per element"]
        lines += aligned_table([["element", "energy [kJ]"]]
                               + [[label, kj(j)] for label, j in lost.items()], {1})
    return "\n".join(lines)


def _lines(result: "CycleResult", indices: list[int]) -> list[int]:
    return [result.rows[i].file_line for i in indices]


def _shown(numbers: list[int]) -> str:
    """The first :data:`SHOWN` numbers, then an ellipsis."""
    return ", ".join(map(str, numbers[:SHOWN])) + (", …" if len(numbers) > SHOWN else "")


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
