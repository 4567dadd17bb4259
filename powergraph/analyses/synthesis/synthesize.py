"""Synthesis for a ratio: which trains give ratio R, with which teeth, ranked.

For each graph (the enumeration up to ``max_links`` links, or the classic trains of
:mod:`~powergraph.analyses.synthesis.synthesize_classics`) and each layout of its teeth
(:mod:`~powergraph.analyses.synthesis.teeth`), every choice of fixed link, input and output
among the coaxial links is searched at once over the layout's tooth space by bounds on the
ratio (:mod:`~powergraph.analyses.synthesis.synthesize_bound`); the feasible tooth sets are
evaluated vectorised and ranked (:mod:`~powergraph.analyses.synthesis.rank`). The search
and the evaluation are mapped with :func:`powergraph.analyses.parallel.cluster` (in
process, on local worker processes, or on a Dask cluster) as units of work, largest
first (:mod:`~powergraph.analyses.synthesis.tasks`); only rows travel back.
docs/synthesis.md.

Examples
--------
>>> from powergraph.analyses.synthesis.synthesize_classics import CLASSICS
>>> result = synthesize(121, graphs=[CLASSICS["RV (2K-H + K-H-V)"]], top=1)  # doctest: +SKIP
>>> result.rows[0].name                                                      # doctest: +SKIP
'RV (2K-H + K-H-V) simple: sun L1 in, carrier+output disk L3 out, ring L0 fixed'
"""
from __future__ import annotations

import dataclasses
import math
from typing import Any, Iterable, Sequence

from powergraph.analyses.parallel import cluster
from powergraph.analyses.synthesis.graph import TrainGraph
from powergraph.analyses.synthesis.rank import SynthesisRow, rank_key, signature
from powergraph.analyses.synthesis.synthesize_classics import CLASSICS
from powergraph.analyses.synthesis.synthesize_search import workable
from powergraph.analyses.synthesis.tasks import SURVEY_BATCH, run_unit, survey, work_units
from powergraph.errors import UsageError
from powergraph.records import record
from powergraph.display import Displayed
from powergraph.format import format_ratio

#: Default largest grid of one layout (a safety limit); larger ones are skipped and reported.
MAX_GRID = 10**7


@record(repr=False)
class SynthesisResult(Displayed):
    """Ranked trains of ratio ``ratio`` (within ``tolerance``, relative).

    ``rows`` are the best ``top`` arrangements (each at its best tooth set); ``feasible``
    counts every feasible tooth set found, ``arrangements`` the distinct arrangements
    with at least one, ``evaluated`` the grid points searched; ``skipped`` lists the
    layouts whose grid exceeded ``max_grid`` (graph, layout, size); ``idle`` names the
    graphs not searched because no arrangement of them works: a gear that meshes one
    gear only, carries nothing and takes no external torque passes no power
    (:func:`~powergraph.analyses.synthesis.synthesize_search.idle_links`).
    """

    ratio: float
    tolerance: float
    teeth: tuple[int, int]
    planets: int
    mesh_efficiency: float
    rows: tuple[SynthesisRow, ...]
    feasible: int
    arrangements: int
    evaluated: int
    graphs: int
    skipped: tuple[tuple[str, str, int], ...]
    idle: tuple[str, ...] = ()

    def _summary(self) -> str:
        return (f"ratio {format_ratio(self.ratio)} ± {self.tolerance:.2%}: {len(self.rows)} "
                f"train(s) shown of {self.arrangements} arrangements")

    def _records(self) -> list[dict[str, Any]]:
        return [{"name": r.name, "ratio": r.ratio, "efficiency": r.efficiency,
                 "backdrive_efficiency": r.backdrive_efficiency,
                 "circulating_power": r.circulating_power,
                 "max_virtual_power_ratio": r.max_virtual_power_ratio, "meshes": r.meshes,
                 "teeth": r.teeth_text()} for r in self.rows]


    def __iter__(self):
        return iter(self.rows)

    def __len__(self) -> int:
        return len(self.rows)

    def __getitem__(self, index: int) -> SynthesisRow:
        return self.rows[index]

    def comparison(self):
        """The rows as a :class:`powergraph.analyses.compare.ComparisonTable`."""
        from powergraph.analyses.compare import ComparisonRow, ComparisonTable

        return ComparisonTable(tuple(ComparisonRow(
            name=r.name, source=None, dof=1, ratio=r.ratio, efficiency=r.efficiency,
            self_locking=r.self_locking, backdrive_efficiency=r.backdrive_efficiency,
            backdrive_self_locking=r.backdrive_self_locking,
            circulating_power=r.circulating_power,
            max_virtual_power_ratio=r.max_virtual_power_ratio, meshes=r.meshes,
            input_power=r.input_power, total_loss=r.input_power * (1.0 - r.efficiency))
            for r in self.rows))

    def to_dict(self) -> dict[str, Any]:
        """Plain data: the search's figures and one dict per row."""
        return {"ratio": self.ratio, "tolerance": self.tolerance, "teeth": list(self.teeth),
                "planets": self.planets, "mesh_efficiency": self.mesh_efficiency,
                "feasible": self.feasible, "arrangements": self.arrangements,
                "evaluated": self.evaluated, "graphs": self.graphs,
                "skipped": [{"graph": g, "layout": lay, "grid": n}
                            for g, lay, n in self.skipped],
                "idle": list(self.idle),
                "rows": [row.to_dict() for row in self.rows]}

    def text_report(self) -> str:
        """The rows in at most 100 columns: train and figures, then the members driven and
        fixed (by role and set), then the teeth; and the search's figures."""
        lines = [f"synthesis for ratio {format_ratio(self.ratio)} ± {self.tolerance:.2%} — "
                 f"{self.feasible} feasible tooth sets in {self.arrangements} arrangements",
                 f"({self.evaluated:.3g} grid points searched, {self.graphs} graphs, teeth "
                 f"{self.teeth[0]}-{self.teeth[1]}, {self.planets} planets, "
                 f"mesh efficiency {self.mesh_efficiency:g})", ""]
        if not self.rows:
            lines.append("no train found")
        else:
            lines += _row_table(self.rows)
        if self.idle:
            lines.append("")
            lines.append(f"{len(self.idle)} graph(s) not searched: in every arrangement a gear "
                         "that meshes one gear only and")
            lines.append("carries nothing is neither fixed, driven nor loaded, so it passes "
                         "no power (an idle gear)")
        if self.skipped:
            lines.append("")
            lines.append(f"{len(self.skipped)} layout(s) not searched (grid over the limit), "
                         f"largest {max(n for *_, n in self.skipped):.3g} points")
        return "\n".join(lines)

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Grouped bars of the rows (delegates to :func:`powergraph.plot.compare.plot_comparison`)."""
        return self.comparison().plot(ax=ax, **kwargs)


#: Width of the text report.
WIDTH = 100


def _row_table(rows: Sequence[SynthesisRow]) -> list[str]:
    """Three lines per row: train and figures; drive; teeth (wrapped at :data:`WIDTH`)."""
    import textwrap

    head = (f"{'#':>2}  {'train (graph, layout)':<42}  {'ratio':>9}  {'eff %':>5}  "
            f"{'back %':>6}  {'circ/P':>6}  {'Pv/P':>5}  {'meshes':>6}")
    out = [head, "-" * len(head)]
    for i, row in enumerate(rows, 1):
        back = ("locks" if row.backdrive_self_locking else
                "-" if row.backdrive_efficiency is None else f"{100 * row.backdrive_efficiency:.2f}")
        circ = row.circulating_power / row.input_power if row.input_power else 0.0
        pv = "-" if row.max_virtual_power_ratio is None else f"{row.max_virtual_power_ratio:.3g}"
        train = textwrap.shorten(f"{row.graph.split(' (')[0]}, {row.layout}", 42,
                                 placeholder="…")
        out.append(f"{i:>2}  {train:<42}  {format_ratio(row.ratio):>9}  "
                   f"{100 * row.efficiency:>5.2f}  {back:>6}  {circ:>6.3f}  {pv:>5}  "
                   f"{row.meshes:>6}")
        out += textwrap.wrap(row.drive_text(), WIDTH, initial_indent="    ",
                             subsequent_indent="      ")
        out += textwrap.wrap("teeth: " + row.member_teeth_text(), WIDTH,
                             initial_indent="    ", subsequent_indent="      ")
    return out


def default_graphs(max_links: int = 6) -> tuple[TrainGraph, ...]:
    """The enumeration's 1-DOF graphs with 3 to ``max_links`` links (those isomorphic to a
    classic train named after it, e.g. ``Wolfrom 3K (5-link d-graph 1)``), plus the coupled
    K-H-V and RV trains, which it does not produce."""
    from powergraph.analyses.synthesis.enumerate import enumerate_trains

    graphs = []
    for n in range(3, max_links + 1):
        found = enumerate_trains(links=n, dof=1)
        names: dict[int | None, str] = {}
        for name, g in CLASSICS.items():
            if g.links == n and not g.couplings:
                index = found.find(g)
                names[index] = f"{names[index]} / {name}" if index in names else name
        graphs += [dataclasses.replace(g, name=f"{names[i]} ({g.name})") if i in names else g
                   for i, g in enumerate(found.graphs)]
    coupled = [g for g in CLASSICS.values() if g.couplings and g.links <= max_links]
    return tuple(graphs) + tuple(coupled)


def synthesize(ratio: float, tolerance: float = 0.005, max_links: int = 6,
               teeth: tuple[int, int] = (12, 120), planets: int = 3,
               mesh_efficiency: float = 0.98, top: int | None = 10,
               graphs: Iterable[TrainGraph] | None = None, scheduler: str | None = None,
               workers: int | None = None, max_grid: int = MAX_GRID) -> SynthesisResult:
    """Trains of ratio ``ratio`` (input speed / output speed) within ``tolerance``.

    Parameters
    ----------
    ratio : target ratio (negative: the output turns the other way)
    tolerance : relative tolerance on the ratio (0.005 = 0.5 %)
    max_links : largest number of links of the default graphs
    teeth : (smallest, largest) tooth number of every gear
    planets : planets spaced equally around the main axis
    mesh_efficiency : basic efficiency of every mesh, in (0, 1]
    top : rows kept (None: all arrangements)
    graphs : the graphs to search (default :func:`default_graphs`)
    scheduler, workers : run on a Dask cluster (:func:`powergraph.analyses.parallel.map_chunks`)
    max_grid : largest grid of one layout searched

    Returns
    -------
    SynthesisResult
    """
    _check(ratio, tolerance, teeth, planets, mesh_efficiency, top, max_grid)
    graphs = tuple(default_graphs(max_links) if graphs is None else graphs)
    for g in graphs:
        if g.dof != 1:
            raise UsageError(f"graph {g.name or g} has {g.dof} degrees of freedom; "
                             "synthesis needs 1-DOF graphs")
    teeth = (int(teeth[0]), int(teeth[1]))
    batches = [[(g, gi) for gi, g in enumerate(graphs)][i:i + SURVEY_BATCH]
               for i in range(0, len(graphs), SURVEY_BATCH)]
    with cluster(scheduler=scheduler, workers=workers) as run:
        surveys = [s for part in run(_survey, [(b, teeth, planets, max_grid) for b in batches])
                   for s in part]
        units = work_units(surveys)
        done = run(run_unit, [(graphs[gi], gi, layouts, float(ratio), float(tolerance), teeth,
                               planets, float(mesh_efficiency)) for gi, layouts, _ in units])
    rows = [row for part in done for row in part]
    idle = tuple(g.name or f"graph {gi}" for gi, g in enumerate(graphs) if not workable(g))
    skipped = [entry for _, part in surveys for entry in part]
    evaluated = sum(size for searched, _ in surveys for _, size in searched)
    ranked, seen = [], set()
    for row in sorted(rows, key=rank_key):
        if signature(row) not in seen:
            seen.add(signature(row))
            ranked.append(row)
    return SynthesisResult(
        ratio=float(ratio), tolerance=float(tolerance), teeth=teeth, planets=planets,
        mesh_efficiency=float(mesh_efficiency),
        rows=tuple(ranked if top is None else ranked[:top]),
        feasible=sum(row.candidates for row in rows), arrangements=len(ranked),
        evaluated=evaluated, graphs=len(graphs), skipped=tuple(skipped), idle=idle)


def _survey(item: tuple) -> list:
    """:func:`~powergraph.analyses.synthesis.tasks.survey` of one batch (one task)."""
    return survey(*item)


def _check(ratio, tolerance, teeth, planets, mesh_efficiency, top, max_grid) -> None:
    def bad(text: str) -> UsageError:
        return UsageError(text)

    if not isinstance(ratio, (int, float)) or not math.isfinite(ratio) or ratio == 0:
        raise bad(f"ratio must be a finite non-zero number, got {ratio!r}")
    if not 0 < tolerance < 1:
        raise bad(f"tolerance must be in (0, 1), got {tolerance!r}")
    if len(teeth) != 2 or not all(float(z).is_integer() for z in teeth) or not (
            3 <= teeth[0] < teeth[1] <= 1000):
        raise bad(f"teeth must be whole numbers LOW < HIGH in 3..1000, got {teeth!r}")
    if not isinstance(planets, int) or planets < 1:
        raise bad(f"planets must be a whole number >= 1, got {planets!r}")
    if not 0 < mesh_efficiency <= 1:
        raise bad(f"mesh efficiency must be in (0, 1], got {mesh_efficiency!r}")
    if top is not None and (not isinstance(top, int) or top < 1):
        raise bad(f"top must be a whole number >= 1, got {top!r}")
    if not isinstance(max_grid, int) or max_grid < 1:
        raise bad(f"max_grid must be a whole number >= 1, got {max_grid!r}")
