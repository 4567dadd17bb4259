"""Lost motion of a whole train: every mesh's play referred to the output, inputs held.

Each mesh's play is a small free rotation ``s`` of its first gear ``a`` (``between[0]``)
relative to gear ``b`` in the carrier's frame: the right-hand side of its Willis row
``(w_a − w_c) − i (w_b − w_c) = s``. With every input held, the output turns by
``S_k · s_k``, where the sensitivity ``S_k`` comes from
:func:`powergraph.kinematics.solve_speeds` with slip 1 on mesh k. The play of gear a is

- for a ``backlash:`` block: j_t / r_a, r_a = m·z_a/2 (Eq. 1 with gear a's radius; the
  paper's own arc-minutes are the internal gear's, j_t / r_int), with j_t the pair's
  ``before`` (``assembly: standard``) or ``after`` (``assembly: compensated``) backlash;
- for ``backlash_arcmin:``: that value, which is defined as gear a's play.

The output's lost motion is the worst-case sum Σ|S_k s_k| and the root-sum-square
√Σ(S_k s_k)². A mesh with ``count`` > 1 (parallel planets) is taken as one play: identical
parts in parallel do not add up.
"""
from __future__ import annotations

import math
from dataclasses import field
from typing import Any

from powergraph.analyses.backlash.pair import PairBacklash, analyse_pair, lost_motion_arcmin
from powergraph.errors import KinematicsError, ModelError, UsageError
from powergraph.kinematics import solve_speeds
from powergraph.model.spec import Link, Model
from powergraph.records import record
from powergraph.result import nothing_to_draw
from powergraph.display import Displayed


@record
class MeshBacklash:
    """One mesh's play and its share of the output's lost motion (arc-minutes)."""

    link: int
    between: tuple[str, str]
    raw_between: tuple[Any, Any]
    carrier: str
    source: str
    play_arcmin: float
    sensitivity: float
    pair: PairBacklash | None = None

    @property
    def output_arcmin(self) -> float:
        """|S_k|·play: this mesh's lost motion seen at the output."""
        return abs(self.sensitivity) * self.play_arcmin

    def to_dict(self) -> dict:
        pair = self.pair
        data = {"link": self.link, "between": list(self.raw_between), "carrier": self.carrier,
                "source": self.source,
                "equivalent_shift": dict(pair.equivalent_shift) if pair else None,
                "eccentric_offset": dict(pair.eccentric_offset) if pair else None,
                "lost_motion_arcmin": dict(pair.lost_motion_arcmin) if pair else None,
                "play_arcmin": self.play_arcmin, "play_gear": self.between[0],
                "output_sensitivity": self.sensitivity, "output_arcmin": self.output_arcmin}
        if pair:
            details = pair.to_dict()
            for key in ("equivalent_shift", "eccentric_offset", "lost_motion_arcmin"):
                details.pop(key)
            data["pair"] = details
        return data


@record(repr=False)
class BacklashReport(Displayed):
    """Per-mesh backlash and the output's lost motion (arc-minutes) of one model."""

    name: str
    output: str
    meshes: tuple[MeshBacklash, ...]
    meshes_without_backlash: tuple[tuple[Any, Any], ...]
    model: Model | None = field(default=None, repr=False, compare=False)

    def _summary(self) -> str:
        return f"{self.name}: {len(self.meshes)} mesh(es) with backlash, output {self.output}"

    def _records(self) -> list[dict[str, Any]]:
        """One row per mesh: its play (arcmin) and how much of it reaches the output."""
        return [{"link": m.link, "between": "-".join(map(str, m.raw_between)),
                 "play_arcmin": m.play_arcmin, "sensitivity": m.sensitivity,
                 "at_output_arcmin": abs(m.play_arcmin * m.sensitivity)}
                for m in self.meshes]


    @property
    def worst_case(self) -> float:
        """Σ |S_k|·play_k (arcmin at the output)."""
        return math.fsum(m.output_arcmin for m in self.meshes)

    @property
    def rss(self) -> float:
        """√Σ (S_k·play_k)² (arcmin at the output)."""
        return math.sqrt(math.fsum(m.output_arcmin ** 2 for m in self.meshes))

    def text_report(self) -> str:
        """The readable report ``powergraph backlash`` prints."""
        from powergraph.analyses.backlash.report import report_text

        return report_text(self.model, self)

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Lost-motion terms of every pair with a ``backlash:`` block, as stacked bars
        (delegates, lazily, to :func:`powergraph.plot.backlash.plot_lost_motion`)."""
        pairs = {f"{a}-{b}": m.pair for m in self.meshes if m.pair is not None
                 for a, b in [m.raw_between]}
        if not pairs:
            raise nothing_to_draw(self, "no mesh has a backlash: block (only "
                                  "backlash_arcmin)")
        from powergraph.plot.backlash import plot_lost_motion

        return plot_lost_motion(pairs, ax=ax, **kwargs)

    def to_dict(self) -> dict:
        """``{name, output, meshes, meshes_without_backlash, output_lost_motion_arcmin:
        {worst_case, rss}}`` (arc-minutes at the output)."""
        return {"name": self.name, "output": self.output,
                "meshes": [m.to_dict() for m in self.meshes],
                "meshes_without_backlash": [list(p) for p in self.meshes_without_backlash],
                "output_lost_motion_arcmin": {"worst_case": self.worst_case, "rss": self.rss}}


def mesh_backlash(model: Model, link_index: int) -> PairBacklash:
    """:func:`analyse_pair` of the ``backlash:`` block on ``links[link_index]``.

    >>> from powergraph.model import load_model
    >>> model = load_model("models/backlash_li2012.yaml")               # doctest: +SKIP
    >>> round(mesh_backlash(model, 0).eccentric_offset["paper"], 3)      # doctest: +SKIP
    2.578
    """
    link = model.links[link_index]
    block = link.blocks.get("backlash") if link.type == "mesh" else None
    if block is None:
        raise UsageError(f"links[{link_index}] is not a mesh with a backlash: block")
    teeth = model.components[block.internal].teeth, model.components[block.external].teeth
    try:
        return analyse_pair(block, *teeth)
    except ModelError as exc:
        raise ModelError(exc.message, f"{link.path}.backlash") from None


def analyse_backlash(model: Model, output: str | int | None = None) -> BacklashReport:
    """Every mesh's backlash, and the lost motion at the output with the inputs held.

    Parameters
    ----------
    model : Model
        A model whose meshes carry ``backlash:`` blocks or ``backlash_arcmin:`` values
        (meshes with neither are taken as having no play).
    output : str or int, optional
        The component at which to read the lost motion; default the one output port.

    Returns
    -------
    BacklashReport

    Raises
    ------
    ModelError
        No mesh carries backlash data, or the train's kinematics are not determined once
        the inputs are held.
    UsageError
        ``output`` is unknown, or the model has several outputs and none was chosen.

    Examples
    --------
    >>> from powergraph.model import model_from_dict
    >>> m = model_from_dict({"name": "pair", "components": {0: {"role": "frame"},
    ...     1: {"teeth": 20}, 2: {"teeth": 60}},
    ...     "links": [{"type": "mesh", "between": [1, 2], "backlash_arcmin": 6.0}],
    ...     "ports": [{"component": 1, "role": "input"}, {"component": 2, "role": "output"}]})
    >>> round(analyse_backlash(m).worst_case, 12)     # 6' on the pinion = 2' on the wheel
    2.0
    """
    target = _output_component(model, output)
    meshes, without = [], []
    for link in model.meshes:
        play = _play(model, link)
        if play is None:
            without.append(link.raw_between)
            continue
        arcmin, pair, source = play
        meshes.append(MeshBacklash(link=link.index, between=link.between,
                                   raw_between=link.raw_between, carrier=link.carrier,
                                   source=source, play_arcmin=arcmin,
                                   sensitivity=_output_sensitivity(model, link.index, target),
                                   pair=pair))
    if not meshes:
        raise ModelError("no mesh carries backlash: or backlash_arcmin:, so there is no lost "
                         "motion to compute", "links")
    return BacklashReport(name=model.name, output=target, meshes=tuple(meshes),
                          meshes_without_backlash=tuple(without), model=model)


def _play(model: Model, link: Link) -> tuple[float, PairBacklash | None, str] | None:
    """(play of gear a in arcmin, pair analysis or None, source) of a mesh, or None."""
    if "backlash_arcmin" in link.blocks:
        return float(link.blocks["backlash_arcmin"]), None, "backlash_arcmin"
    if "backlash" not in link.blocks:
        return None
    pair = mesh_backlash(model, link.index)
    j_t = pair.backlash_mm["after" if pair.assembly == "compensated" else "before"]
    gear_a = link.between[0]
    return lost_motion_arcmin(j_t, pair.module, pair.teeth[gear_a]), pair, "backlash"


def _output_component(model: Model, output: str | int | None) -> str:
    if output is None:
        outputs = model.outputs
        if len(outputs) != 1:
            raise UsageError(f"the model has {len(outputs)} output ports; choose the one at "
                             "which to read the lost motion (--output ID)")
        return outputs[0].component
    if str(output) not in model.components:
        raise UsageError(f"unknown component {str(output)!r} for the output")
    return str(output)


def _output_sensitivity(model: Model, link_index: int, output: str | None = None) -> float:
    """d(output angle)/d(slip s of gear a in mesh ``link_index``), every input held.

    >>> from powergraph.model import model_from_dict
    >>> m = model_from_dict({"name": "pair", "components": {0: {"role": "frame"},
    ...     1: {"teeth": 20}, 2: {"teeth": 60}}, "links": [{"type": "mesh", "between": [1, 2]}],
    ...     "ports": [{"component": 1, "role": "input"}, {"component": 2, "role": "output"}]})
    >>> _output_sensitivity(m, 0)   # (w1 - 0) - (-3)(w2 - 0) = s with w1 = 0
    0.3333333333333333
    """
    target = _output_component(model, output)
    held = {port.component: 0.0 for port in model.inputs}
    try:
        kinematics = solve_speeds(model, speeds=held, slips={link_index: 1.0})
    except KinematicsError as exc:
        raise KinematicsError(f"with every input held (to refer backlash to the output): "
                              f"{exc.message}", exc.path) from None
    return kinematics.speed(target)
