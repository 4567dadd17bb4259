"""Text, JSON rows and CSV views of a :class:`~powergraph.analyses.cycle.CycleResult`,
read from its columns :data:`CHUNK` rows at a time (the CSV is written as it goes).

With machines, each row also carries the flows (:func:`flow_columns`): in JSON
``port_power``, ``machines`` and ``buses``; in CSV after :data:`COLUMNS`, in the points
file's own syntax, ``engine.power [W]``, ``MG1.speed [rad/s]``, ``MG1.torque [N*m]``,
``MG1.power [W]``, ``MG1.electrical_power [W]``, ``MG1.state``, ``dc.battery [W]``."""
from __future__ import annotations

import csv
import io
from math import isnan
from typing import Any, Iterator

import numpy as np

from powergraph.analyses.cycle_columns import (LOCKED, MACHINE_KEYS, SELF_LOCKING,
                                               machine_states)
from powergraph.format import aligned_table, format_number

#: CSV columns of the per-row results, with their units.
COLUMNS = (("row", None), ("duration", "s"), ("mode", None), ("power_in", "W"),
           ("power_out", "W"), ("loss", "W"), ("efficiency", "-"), ("verdict", None),
           ("electrical_share", "-"), ("negative_split", None), ("warnings", None))
#: The unit of each machine quantity in the CSV header (SI).
MACHINE_UNITS = {"speed": "rad/s", "torque": "N*m", "power": "W", "electrical_power": "W"}
#: Rows named one by one in the text report, per list.
SHOWN = 12
#: Rows turned into Python values at a time (JSON rows, CSV lines).
CHUNK = 1 << 16


def text_report(result: "CycleResult") -> str:
    """Totals first (energies in kJ), then the energy lost per element. The totals are
    over the rows solved; the rows left out (``keep_going``) are counted and named."""
    kj = lambda joules: format_number(joules / 1e3, 6)   # noqa: E731
    eff, lost = result.efficiency, result.energy_lost
    lines = [f"{result.name} — duty cycle, {len(result.durations)} operating points "
             f"({result.method})", "",
             f"time                {format_number(result.time, 6)} s",
             f"energy in           {kj(result.energy_in)} kJ",
             f"energy out          {kj(result.energy_out)} kJ",
             f"energy lost         {kj(sum(lost.values()))} kJ",
             "cycle efficiency    " + (f"{eff:.2%}" if eff is not None else
                                       "undefined (no energy enters)")]
    left_out = np.flatnonzero(result.failed)
    if len(left_out):
        lines.append(f"left out            {len(left_out)} row(s), "
                     f"{format_number(result.left_out_time, 6)} s (cannot be solved; file "
                     f"lines {_shown(result, left_out)})")
    if result.with_machines.any():
        lines.append(f"negative split      {format_number(result.negative_split_time, 6)} s "
                     "(power circulating through a bus)")
    for bus, joules in result.battery_energy.items():
        lines.append(f"battery {bus}".ljust(19) + f" {kj(joules)} kJ into the bus"
                     + (" (charged)" if joules < 0 else ""))
    codes = result.verdict_codes
    locked = np.flatnonzero((codes == LOCKED) | (codes == SELF_LOCKING))
    if len(locked):
        lines.append(f"rows that lock      {_shown(result, locked)} (file lines)")
    for code, rows in result.warnings.items():
        lines.append(f"warning: {code} in {len(rows)} row(s), file lines "
                     f"{_shown(result, rows)} (solve one for the details)")
    lines += [f"warning: row {result.lines[i]}: {result.verdict_texts[codes[i]][7:]}"
              for i in left_out[:SHOWN].tolist()]
    if len(left_out) > SHOWN:
        lines.append(f"warning: {len(left_out) - SHOWN} more row(s) cannot be solved "
                     "(their verdicts: --json or -o)")
    modes = result.time_per_mode
    if modes and list(modes) != ["-"]:
        lines += ["", "time per mode"]
        lines += aligned_table([["mode", "time [s]"]] + [[m, format_number(t, 6)]
                                                         for m, t in modes.items()], {1})
    if lost:
        lines += ["", "energy lost per element"]
        lines += aligned_table([["element", "energy [kJ]"]]
                               + [[label, kj(j)] for label, j in lost.items()], {1})
    return "\n".join(lines)


def _shown(result: "CycleResult", rows: np.ndarray) -> str:
    """The file lines of the first :data:`SHOWN` ``rows`` (indices), then an ellipsis."""
    shown = result.lines[rows[:SHOWN]].tolist()
    return ", ".join(map(str, shown)) + (", …" if len(rows) > SHOWN else "")


def _optional(values: np.ndarray) -> list[float | None]:
    """The values, None for NaN."""
    return [None if isnan(v) else v for v in values.tolist()]


def _parts(n: int) -> Iterator[slice]:
    """The rows, :data:`CHUNK` at a time."""
    return (slice(start, min(start + CHUNK, n)) for start in range(0, n, CHUNK))


def _warnings(result: "CycleResult", part: slice, lists: bool) -> list:
    """The warning codes of the rows ``part``: a list per row, or ``code;code`` text."""
    size = part.stop - part.start
    out: list = [[] for _ in range(size)] if lists else [""] * size
    for code, rows in result.warnings.items():
        low, high = np.searchsorted(rows, [part.start, part.stop]).tolist()
        for k in (rows[low:high] - part.start).tolist():
            if lists:
                out[k].append(code)
            else:
                out[k] = f"{out[k]};{code}" if out[k] else code
    return out


#: The keys of a row in ``to_dict()["rows"]``, in order.
ROW_KEYS = ("row", "line", "duration", "mode", "power_in", "power_out", "loss", "efficiency",
            "verdict", "losses", "electrical_share", "negative_split", "warnings",
            "port_power", "machines", "buses")


def row_dicts(result: "CycleResult") -> list[dict[str, Any]]:
    """Each row as :meth:`CycleRow.to_dict` gives it (the ``rows`` of ``to_dict()``),
    built from the columns a chunk at a time."""
    out: list[dict[str, Any]] = []
    labels = list(result.losses)
    for part in _parts(len(result.durations)):
        size = part.stop - part.start
        losses = zip(*(result.losses[label][part].tolist() for label in labels))
        split = zip(result.negative_split[part].tolist(), result.with_machines[part].tolist())
        columns = (
            range(part.start, part.stop), result.lines[part].tolist(),
            result.durations[part].tolist(),
            [None] * size if result.mode_codes is None else
            [result.mode_names[c] for c in result.mode_codes[part].tolist()],
            result.power_in[part].tolist(), result.power_out[part].tolist(),
            result.loss[part].tolist(), _optional(result.efficiencies[part]),
            [result.verdict_texts[c] for c in result.verdict_codes[part].tolist()],
            ([{k: v for k, v in zip(labels, row) if not isnan(v)} for row in losses]
             if labels else [{} for _ in range(size)]),
            _optional(result.electrical_share[part]), [s if m else None for s, m in split],
            _warnings(result, part, lists=True), *_flow_dicts(result, part))
        out += [dict(zip(ROW_KEYS, values)) for values in zip(*columns)]
    return out


def _flow_dicts(result: "CycleResult", part: slice) -> tuple[list, list, list]:
    """Per row of ``part``: ``port_power``, ``machines`` (each with its ``state``) and
    ``buses``, empty in a row not solved (and without machines)."""
    size = part.stop - part.start
    if not result.machines:
        return [{}] * size, [{}] * size, [{}] * size
    ports = _by_row({k: v[part] for k, v in result.port_power.items()})
    buses = [{bus: {"battery_power": w} for bus, w in row.items()}
             for row in _by_row({k: v[part] for k, v in result.battery_power.items()})]
    machines: list[dict] = [{} for _ in range(size)]
    for name, quantities in result.machines.items():
        states = machine_states(quantities["power"][part], quantities["speed"][part])
        for k, values in enumerate(zip(*(quantities[key][part].tolist()
                                          for key in MACHINE_KEYS))):
            if states[k]:
                machines[k][name] = {**{key: None if isnan(v) else v
                                        for key, v in zip(MACHINE_KEYS, values)},
                                     "state": states[k]}
    return ports, machines, buses


def _by_row(columns: dict[str, np.ndarray]) -> list[dict[str, float]]:
    """``{name: value}`` per row from columns by name, without the NaN values."""
    names = list(columns)
    return [{k: v for k, v in zip(names, row) if not isnan(v)}
            for row in zip(*(columns[k].tolist() for k in names))]


def flow_columns(result: "CycleResult") -> list[tuple[str, np.ndarray, bool]]:
    """``(header, values, state)`` of each flow column of the CSV: each other port's
    power, each machine's quantities and state (``state`` True: the machine's states,
    from its quantities ``values``), each bus's battery power."""
    out = [(f"{name}.power [W]", values, False)
           for name, values in result.port_power.items()]
    for name, quantities in result.machines.items():
        out += [(f"{name}.{key} [{MACHINE_UNITS[key]}]", quantities[key], False)
                for key in MACHINE_KEYS]
        out.append((f"{name}.state", quantities, True))
    out += [(f"{bus}.battery [W]", values, False)
            for bus, values in result.battery_power.items()]
    return out


def to_csv(result: "CycleResult", path: Any = None) -> str | None:
    """The per-row results as CSV (units in the header), written to ``path`` as the rows
    are formatted, or returned as text when ``path`` is None."""
    if path is None:
        out = io.StringIO()
        _write_csv(result, out)
        return out.getvalue()
    with open(path, "w", encoding="utf-8", newline="") as f:
        _write_csv(result, f)
    return None


def _write_csv(result: "CycleResult", out: Any) -> None:
    """The header, then the rows a chunk at a time: numbers by their repr (None: an empty
    cell), each distinct text (verdict, mode, warnings) quoted once as the csv module
    quotes a cell."""
    flows = flow_columns(result)
    csv.writer(out, lineterminator="\n").writerow(
        [f"{name} [{unit}]" if unit else name for name, unit in COLUMNS]
        + [header for header, _, _ in flows])
    verdicts = [_cell(text) for text in result.verdict_texts]
    modes = [_cell(name) for name in result.mode_names]
    warnings: dict[str, str] = {}
    words = ("false", "true")
    for part in _parts(len(result.durations)):
        size = part.stop - part.start
        columns = (
            map(str, range(part.start, part.stop)), map(repr, result.durations[part].tolist()),
            [""] * size if result.mode_codes is None else
            [modes[c] for c in result.mode_codes[part].tolist()],
            map(repr, result.power_in[part].tolist()),
            map(repr, result.power_out[part].tolist()), map(repr, result.loss[part].tolist()),
            _reprs(result.efficiencies[part]),
            [verdicts[c] for c in result.verdict_codes[part].tolist()],
            _reprs(result.electrical_share[part]),
            [words[s] if m else "" for s, m in zip(result.negative_split[part].tolist(),
                                                   result.with_machines[part].tolist())],
            [warnings[w] if w in warnings else warnings.setdefault(w, _cell(w))
             for w in _warnings(result, part, lists=False)],
            *(machine_states(values["power"][part], values["speed"][part]) if state
              else _reprs(values[part])
              for _, values, state in flows))
        out.write("\n".join(map(",".join, zip(*columns))) + "\n")


def _reprs(values: np.ndarray) -> list[str]:
    """The values' reprs, an empty cell for NaN."""
    if not np.isnan(values).any():
        return list(map(repr, values.tolist()))
    return ["" if isnan(v) else repr(v) for v in values.tolist()]


def _cell(text: str) -> str:
    """``text`` as the csv module writes it in a row of several cells (quoted when it
    holds a comma, a quote or a line end)."""
    if not text:
        return ""
    line = io.StringIO()
    csv.writer(line, lineterminator="\n").writerow([text])
    return line.getvalue()[:-1]
