"""Side-by-side comparison of trains: ratio, efficiency both ways, circulation, rolling.

Each row is the answer of the train's case (:class:`powergraph.statics.case.TrainCase`),
forward and driven from its output, so a row always matches ``powergraph solve [--mode M]
[--backdrive]`` exactly.

Examples
--------
>>> from powergraph.model import load_model
>>> rows = compare_models([load_model("models/rv40e_wang2021.yaml")], mesh_efficiency=0.99)  # doctest: +SKIP
>>> rows[0].ratio                                                                   # doctest: +SKIP
121.0
>>> print(rows.text_report())                                                       # doctest: +SKIP
"""
from __future__ import annotations

import math
from dataclasses import asdict
from typing import Any, Iterable, Iterator

from powergraph.errors import PowerGraphError
from powergraph.model.spec import Model
from powergraph.format import (POWER_UNITS, VOLUME_UNITS, aligned_table, format_column,
                               format_fixed, format_number, format_ratio)
from powergraph.records import record
from powergraph.statics.case import TrainCase
from powergraph.display import Displayed

#: Text-table columns: (row attribute, header, how a cell is written). A header with
#: ``{unit}`` takes the one unit its column is written in (powergraph.format).
COLUMNS = (("name", "train", "text"), ("ratio", "ratio", "ratio"),
           ("efficiency", "eff. %", "percent"), ("backdrive_efficiency", "back %", "percent"),
           ("backdrive_self_locking", "locks back", "text"),
           ("circulating_power", "circ. {unit}", "power"),
           ("max_virtual_power_ratio", "max Pv/P", "number"), ("meshes", "meshes", "text"),
           ("volume_mm3", "volume {unit}", "volume"),
           ("power_density_kw_per_l", "kW/L", "number"))


@record
class ComparisonRow:
    """One train's figures of merit (powers in W, volume in mm³, density in kW/L).

    ``efficiency`` and ``backdrive_efficiency`` are read from the actual flows, as
    ``solve`` reports them (power out at the ports / power in at the ports: 0 when the
    train self-locks that way); ``formal_efficiency`` and ``backdrive_formal_efficiency``
    are declared output / declared input, the papers' figure, negative when it self-locks.
    ``backdrive_efficiency`` is None (with ``backdrive_note``) where back-driving is not
    defined (several inputs or outputs); a back-drive that locks (no consistent direction
    pattern: docs/locking.md) has efficiency 0 and the locking reason in
    ``backdrive_note``.
    """

    name: str
    source: str | None
    dof: int
    ratio: float | None
    efficiency: float
    self_locking: bool
    backdrive_efficiency: float | None
    backdrive_self_locking: bool | None
    circulating_power: float
    max_virtual_power_ratio: float
    meshes: int
    input_power: float
    total_loss: float
    volume_mm3: float | None = None
    power_density_kw_per_l: float | None = None
    backdrive_note: str | None = None
    formal_efficiency: float | None = None
    backdrive_formal_efficiency: float | None = None

    def to_dict(self) -> dict:
        """Every field; ``max_virtual_power_ratio`` is the largest power a mesh passes in
        its carrier's frame over the input power."""
        return asdict(self)


@record(repr=False)
class ComparisonTable(Displayed):
    """Rows of several trains; a sequence of :class:`ComparisonRow` (``table[0]``,
    ``for row in table``) that follows :class:`powergraph.result.Result`."""

    rows: tuple[ComparisonRow, ...]

    def _summary(self) -> str:
        return f"{len(self.rows)} train(s): " + ", ".join(r.name for r in self.rows[:3]) \
            + (", ..." if len(self.rows) > 3 else "")

    def _records(self) -> list[dict[str, Any]]:
        return [row.to_dict() for row in self.rows]


    def __iter__(self) -> Iterator[ComparisonRow]:
        return iter(self.rows)

    def __len__(self) -> int:
        return len(self.rows)

    def __getitem__(self, index: int) -> ComparisonRow:
        return self.rows[index]

    def to_dict(self) -> dict[str, Any]:
        """``{"rows": [row.to_dict(), ...]}`` (``compare --json`` prints the list)."""
        return {"rows": [row.to_dict() for row in self.rows]}

    def text_report(self) -> str:
        """Aligned text table, one row per train; columns with no data are left out.
        A self-locking direction shows "locks" instead of its efficiency; the formal
        (<= 0) efficiency stays in :meth:`to_dict` (docs/locking.md)."""
        columns = [c for c in COLUMNS if any(getattr(r, c[0]) is not None for r in self.rows)]
        header, body = [], [[] for _ in self.rows]
        for key, title, kind in columns:
            unit, cells = _column([getattr(row, key) for row in self.rows], kind)
            for cell, row, out in zip(cells, self.rows, body):
                out.append("locks" if key in LOCKING and getattr(row, LOCKING[key]) else cell)
            header.append(title.format(unit=unit))
        return "\n".join(aligned_table([header, *body], set(range(1, len(columns)))))

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Grouped bars (delegates, lazily, to :func:`powergraph.plot.compare.plot_comparison`)."""
        from powergraph.plot.compare import plot_comparison

        return plot_comparison(self.rows, ax=ax, **kwargs)


#: Efficiency columns shown as "locks" where the train self-locks that way.
LOCKING = {"efficiency": "self_locking", "backdrive_efficiency": "backdrive_self_locking"}


def _column(values: list[Any], kind: str) -> tuple[str, list[str]]:
    """``(unit, cells)`` of one column, in one unit (powergraph.format)."""
    if kind in ("power", "volume"):
        return format_column(values, POWER_UNITS if kind == "power" else VOLUME_UNITS)
    if kind == "ratio":
        return "", [format_ratio(v) for v in values]
    if kind == "percent":
        return "%", [format_fixed(None if v is None else 100 * v) for v in values]
    if kind == "number":
        return "", [format_number(v, 3) for v in values]
    return "", ["-" if v is None else ("yes" if v else "no") if isinstance(v, bool) else str(v)
                for v in values]


def compare_models(models: Iterable[Model], mesh_efficiency: float | None = None
                   ) -> ComparisonTable:
    """One :class:`ComparisonRow` per model, optionally all meshes at ``mesh_efficiency``.

    Parameters
    ----------
    models : iterable of Model
    mesh_efficiency : float, optional
        Compare at equal mesh quality: every mesh's basic efficiency set to this.

    Returns
    -------
    ComparisonTable
        Indexable and iterable like a list of rows.
    """
    rows = []
    for model in models:
        if mesh_efficiency is not None:
            model = model.with_mesh_efficiency(mesh_efficiency)
        rows.append(compare_row(model))
    return ComparisonTable(tuple(rows))


def compare_row(model: Model, mode: str | None = None) -> ComparisonRow:
    """The figures of merit of one model, in ``mode`` for a model with modes (see
    :class:`ComparisonRow`): the case forward and back-driven
    (:class:`~powergraph.statics.case.TrainCase`), each with its freewheels decided, so a
    row matches ``powergraph solve [--mode M] [--backdrive]``."""
    case = TrainCase.of(model, mode)
    forward = case.point().required().result
    back, note = _backdrive(model, mode)
    largest = max((e.carrier_frame_power for e in forward.meshes), default=0.0)
    volume, density = _volume(model, forward.output_power)
    return ComparisonRow(
        name=forward.model.name if mode is not None else model.name, source=model.source,
        dof=forward.dof, ratio=forward.ratio,
        efficiency=forward.efficiency, self_locking=forward.self_locking,
        backdrive_efficiency=back.efficiency if back is not None else None,
        backdrive_self_locking=back.self_locking if back is not None else None,
        circulating_power=forward.circulating_power,
        max_virtual_power_ratio=largest / forward.input_power if forward.input_power else 0.0,
        meshes=len(forward.meshes), input_power=forward.input_power,
        total_loss=forward.total_loss, volume_mm3=volume, power_density_kw_per_l=density,
        backdrive_note=note, formal_efficiency=_finite(forward.formal_efficiency),
        backdrive_formal_efficiency=_finite(back.formal_efficiency) if back is not None
        else None)


def _finite(value: float) -> float | None:
    return value if math.isfinite(value) else None


def _backdrive(model: Model, mode: str | None) -> tuple[Any, str | None]:
    """The case back-driven at the forward input power (None with a note when not defined
    or not solvable)."""
    if len(model.inputs) != 1 or len(model.outputs) != 1:
        return None, "back-driving needs one input and one output"
    try:
        point = TrainCase.of(model, mode, backdrive=True).point()
    except PowerGraphError as exc:
        return None, str(exc)
    if point.result is None:
        return None, f"coasting: {point.verdict}"
    result = point.result
    return result, f"locks: {result.lock.reason}" if result.lock is not None else None


def _volume(model: Model, output_power: float) -> tuple[float | None, float | None]:
    if not any(c.geometry is not None for c in model.components.values()):
        return None, None
    from powergraph.analyses.volume import model_volume

    result = model_volume(model)
    if result is None or result.total_mm3 <= 0:
        return None, None
    return result.total_mm3, result.power_density(output_power)
