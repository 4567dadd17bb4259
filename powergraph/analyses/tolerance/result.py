"""The result of a tolerance analysis: a frozen dataclass with JSON, text and plot."""
from __future__ import annotations

from dataclasses import field
from typing import Any, Mapping

import numpy as np

from powergraph.analyses.tolerance.stats import QUANTILES, Yield
from powergraph.format import aligned_table, format_fixed, format_number
from powergraph.display import Displayed
from powergraph.records import record

LABELS = {"lost_motion_arcmin": ("lost motion", "arcmin"),
          "fluctuation_percent": ("ratio fluctuation", "%"),
          "efficiency": ("efficiency", "")}
#: The output whose Sobol indices are the top-level ``sensitivity`` of the JSON.
PRIMARY = ("lost_motion_arcmin", "fluctuation_percent", "efficiency")


@record(eq=False, repr=False)
class ToleranceResult(Displayed):
    """Outputs of ``samples`` sampled units, yields of the specifications, sensitivities.

    Attributes
    ----------
    values : mapping
        ``{output: array}`` of every unit (read-only).
    outputs : mapping
        ``{output: {mean, sd, p50, p95, p99_73, max, min, failed}}``.
    yields : tuple of Yield
    sensitivity : mapping
        ``{output: {PATH: {first, total, first_conf, total_conf}}}`` (Sobol, SALib).
    fluctuation_tables : mapping
        ``{link: {errors, values, interpolation_error_bound}}`` where the profile error
        varies.
    labels : mapping
        ``{PATH: what it is}`` in the model's names (``mesh cycloid gear-needle gear``).
    """

    name: str
    samples: int
    seed: int
    tolerances: Any
    values: Mapping[str, np.ndarray]
    outputs: Mapping[str, dict]
    yields: tuple[Yield, ...]
    sensitivity: Mapping[str, dict]
    sobol_samples: int = 0
    fluctuation_tables: Mapping[int, dict] = field(default_factory=dict)
    labels: Mapping[str, str] = field(default_factory=dict)

    def _summary(self) -> str:
        return f"{self.name}: {self.samples} units (seed {self.seed})"

    def _records(self) -> list[dict[str, Any]]:
        """One row per output: its unit and statistics."""
        return [{"output": name, "unit": self.output_label(name)[1] or "-",
                 **{k: s.get(k) for k in ("mean", "sd", *QUANTILES, "min", "max")}}
                for name, s in self.outputs.items()]

    @staticmethod
    def output_label(output: str) -> tuple[str, str]:
        """What an output is and its unit, for reports and figures.

        Parameters
        ----------
        output : str
            An output name (a key of ``values``).

        Returns
        -------
        tuple of str
            ``(what, unit)``: ``("lost motion", "arcmin")``; ``(output, "")`` for a name
            without a label.
        """
        return LABELS.get(output, (output, ""))

    @property
    def primary(self) -> str | None:
        """The output the top-level sensitivity describes (lost motion first)."""
        return next((o for o in PRIMARY if o in self.sensitivity), None)

    def ranked(self, output: str | None = None) -> list[tuple[str, dict]]:
        """``[(PATH, indices)]`` by decreasing total index."""
        output = output or self.primary
        if output is None:
            return []
        return sorted(self.sensitivity[output].items(), key=lambda kv: -kv[1]["total"])

    def to_dict(self) -> dict:
        primary = self.primary
        return {
            "name": self.name, "samples": self.samples, "seed": self.seed,
            "outputs": {k: dict(v) for k, v in self.outputs.items()},
            "yield": {y.spec.text: y.to_dict() for y in self.yields},
            "yield_interval": "Wilson score, 95 %",
            "sensitivity": {p: {"first": s["first"], "total": s["total"]}
                            for p, s in self.ranked(primary)} if primary else {},
            "sensitivity_output": primary,
            "sensitivity_by_output": {o: dict(self.ranked(o)) for o in self.sensitivity},
            "sobol_samples": self.sobol_samples,
            "tolerances": self.tolerances.to_dict(),
            "fluctuation_tables": {str(k): v for k, v in self.fluctuation_tables.items()},
        }

    def text_report(self) -> str:
        lines = [f"{self.name} — tolerance analysis, {self.samples} units (seed {self.seed})",
                 ""]
        header = ["output", "mean", "sd", *QUANTILES, "max"]
        rows = [header]
        for name, s in self.outputs.items():
            label, unit = self.output_label(name)
            rows.append([f"{label}{f' ({unit})' if unit else ''}",
                         *(_num(s[k]) for k in ("mean", "sd", *QUANTILES, "max"))])
            if s.get("failed"):
                rows[-1][0] += f" [{s['failed']} not computed]"
        lines += _table(rows)
        if self.yields:
            lines += ["", "yield (95 % Wilson score interval)"]
            for y in self.yields:
                low, high = y.interval
                lines.append(f"  {y.spec.text:<28} {100 * y.fraction:8.4f} %   "
                             f"[{100 * low:.4f}, {100 * high:.4f}] %")
        for output in self.sensitivity:
            lines += ["", f"Sobol indices of {self.output_label(output)[0]} "
                          f"(SALib, N = {self.sobol_samples}), by total index"]
            rows = [["PATH", "what", "first", "total"]]
            rows += [[p, self.labels.get(p, ""), _index(s["first"]), _index(s["total"])]
                     for p, s in self.ranked(output)]
            lines += _table(rows)
        for link, table in self.fluctuation_tables.items():
            lines += ["", f"fluctuation of links[{link}]: linear interpolation on "
                          f"{len(table['errors'])} profile errors, error <= "
                          f"{table['interpolation_error_bound']:.2g} % (estimated)"]
        return "\n".join(lines)

    def plot(self, ax=None):
        """Histograms of the outputs (with spec lines) and the tornado chart of the indices.

        Delegates to :func:`powergraph.plot.tolerance.plot_tolerance`.
        """
        from powergraph.plot.tolerance import plot_tolerance

        return plot_tolerance(self, ax=ax)


def _num(value: float) -> str:
    return format_number(value, 6)


def _index(value: float) -> str:
    """A Sobol index to three decimals (never ``-0.000``)."""
    return format_fixed(value, 3)


def _table(rows: list[list[str]]) -> list[str]:
    """Rows padded to widths from their cells: text columns left-aligned, numbers right."""
    numeric = {i for i in range(len(rows[0])) if rows[0][i] not in ("output", "PATH", "what")}
    return aligned_table(rows, numeric, rules_after=())
