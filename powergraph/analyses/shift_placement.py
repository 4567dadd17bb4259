"""Place clutches and brakes on a 2-DOF gearset for a set of ratios (docs/modes.md): the
first step of the automatic-transmission synthesis.

A gearset with two degrees of freedom (two planetary sets sharing two members, a
Ravigneaux set...) gives one ratio per pair of constraints. The candidates, on its coaxial
members other than the output (the nodes of its levers, :mod:`~powergraph.analyses.lever`):

- a **clutch** joining the input shaft to member X together with a **brake** holding
  member Y: ``w_X = 1, w_Y = 0``, ratio ``1/w_out``;
- two clutches, to members X and Z: ``w_X = w_Z = 1``, the set turns as a block (ratio 1).

Each target ratio needs a gear state within the tolerance; a plan takes one state per
target (a different one for each) and the shift elements they use. Plans are ranked by the
number of elements, then by the largest ratio error. The speeds come from the kinematics
(:func:`~powergraph.kinematics.solve_speeds`), the one copy of the Willis relations; the
plan, written as a model with a modes table (:func:`transmission_document`), then goes
through the gear table, which solves every mode with its losses and checks it.

Examples
--------
>>> from powergraph.model import load_model
>>> gearset = load_model("models/gearsets/simpson.yaml")
>>> best = place_shift_elements(gearset, [7/3, 4/3, 1, -3]).plans[0]
>>> best.size, best.modes
(4, {'1': ['C1', 'B1'], '2': ['C1', 'B2'], '3': ['C1', 'C2'], 'R': ['C2', 'B1']})
"""
from __future__ import annotations

import itertools
from dataclasses import field
from typing import Any, Mapping, Sequence

from powergraph.display import Displayed
from powergraph.errors import PowerGraphError, UsageError
from powergraph.kinematics import degrees_of_freedom, solve_speeds
from powergraph.model.spec import Model
from powergraph.records import record

#: Combinations of gear states tried at most (each target keeps its best states first).
MAX_COMBINATIONS = 200_000
#: A gear state whose output turns slower than this (input at 1) gives no usable ratio.
STANDSTILL = 1e-9


@record
class GearState:
    """One pair of engaged elements: input clutches to ``clutches`` (components), brakes
    on ``brakes``, and the ratio (input speed / output speed) they give."""

    clutches: tuple[str, ...]
    brakes: tuple[str, ...]
    ratio: float

    @property
    def elements(self) -> tuple[tuple[str, str], ...]:
        return (tuple(("clutch", c) for c in self.clutches)
                + tuple(("brake", b) for b in self.brakes))


@record
class ShiftPlan:
    """A set of shift elements and the state of each target gear: ``gears[i]`` is the
    state for ``targets[i]``; ``names`` maps ``(kind, member)`` to the element's name."""

    targets: tuple[float, ...]
    gears: tuple[GearState, ...]
    names: Mapping[tuple[str, str], str]

    @property
    def size(self) -> int:
        """Number of shift elements."""
        return len(self.names)

    @property
    def error(self) -> float:
        """The largest relative ratio error over the gears."""
        return max(abs(g.ratio - t) / abs(t) for g, t in zip(self.gears, self.targets))

    @property
    def modes(self) -> dict[str, list[str]]:
        """``{mode name: engaged elements}``: forward gears 1, 2, ... in the order given,
        reverse gears R (R1, R2, ... when several)."""
        reverse = sum(t < 0 for t in self.targets)
        out, forward, back = {}, 0, 0
        for target, gear in zip(self.targets, self.gears):
            if target > 0:
                forward += 1
                name = str(forward)
            else:
                back += 1
                name = "R" if reverse == 1 else f"R{back}"
            out[name] = sorted((self.names[e] for e in gear.elements),
                               key=lambda n: (n[0] != "C", n))
        return out

    def to_dict(self, raw=str) -> dict[str, Any]:
        return {"size": self.size, "error": self.error,
                "elements": [{"name": n, "kind": k, "member": raw(m)}
                             for (k, m), n in self.names.items()],
                "modes": [{"mode": name, "target": t, "ratio": g.ratio, "engaged": engaged}
                          for (name, engaged), t, g in zip(self.modes.items(), self.targets,
                                                           self.gears)]}


@record(repr=False)
class ShiftPlacement(Displayed):
    """The plans found for a gearset, best first, and the gear states they came from."""

    model: Model = field(compare=False)
    targets: tuple[float, ...]
    tolerance: float
    states: tuple[GearState, ...]
    plans: tuple[ShiftPlan, ...]

    @property
    def name(self) -> str:
        return self.model.name

    def _summary(self) -> str:
        best = f"best {self.plans[0].size} elements" if self.plans else "no plan"
        return f"{self.name}: {len(self.states)} gear states, {best}"

    def to_dict(self) -> dict[str, Any]:
        raw = self.model.raw_id
        return {"name": self.name, "targets": list(self.targets), "tolerance": self.tolerance,
                "states": [{"clutches": [raw(c) for c in s.clutches],
                            "brakes": [raw(b) for b in s.brakes], "ratio": s.ratio}
                           for s in self.states],
                "plans": [p.to_dict(raw) for p in self.plans]}

    def text_report(self) -> str:
        from powergraph.analyses.shift_placement_report import text_report

        return text_report(self)


def place_shift_elements(model: Model, ratios: Sequence[float], tolerance: float = 0.01,
                         top: int = 5) -> ShiftPlacement:
    """Clutches (from the input shaft) and brakes on the coaxial members of a 2-DOF
    gearset that give every ratio of ``ratios`` within ``tolerance`` (relative).

    Parameters
    ----------
    model : Model
        The gearset: two degrees of freedom, one output port, no shift elements.
    ratios : sequence of float
        Target ratios (input speed / output speed; negative for reverse), one per gear.
    tolerance : float
        Relative ratio error allowed.
    top : int
        Plans kept, best first (fewest elements, then smallest error).

    Returns
    -------
    ShiftPlacement
    """
    output = _check_gearset(model)
    targets = tuple(float(r) for r in ratios)
    if not targets or any(t == 0 for t in targets):
        raise UsageError("give at least one ratio, none of them 0")
    states = gear_states(model, output)
    if not states:
        raise UsageError("the gearset gives no ratio with one clutch and one brake or two "
                         "clutches on its coaxial members (suns, rings, carriers)")
    given = ", ".join(f"{r:.4g}" for r in sorted({round(s.ratio, 12) for s in states}))
    per_target = [sorted((s for s in states if abs(s.ratio - t) <= tolerance * abs(t)),
                         key=lambda s, t=t: abs(s.ratio - t)) for t in targets]
    for target, found in zip(targets, per_target):
        if not found:
            raise UsageError(f"no pair of shift elements gives ratio {target:g} within "
                             f"{tolerance:.3g} on this gearset; its gear states give "
                             f"{given}")
    plans = _best_plans(targets, per_target, top)
    if not plans:
        raise UsageError("no plan: the targets cannot each have a gear state of their own "
                         "(two of them need the same pair of elements)")
    return ShiftPlacement(model, targets, tolerance, states, plans)


def gear_states(model: Model, output: str) -> tuple[GearState, ...]:
    """Every clutch + brake and clutch + clutch state of the gearset with a finite,
    non-zero ratio."""
    members = _members(model, output)
    states = []
    for x, y in itertools.permutations(members, 2):
        ratio = _ratio(model, {x: 1.0, y: 0.0}, output)
        if ratio is not None:
            states.append(GearState((x,), (y,), ratio))
    for x, z in itertools.combinations(members, 2):
        ratio = _ratio(model, {x: 1.0, z: 1.0}, output)
        if ratio is not None:
            states.append(GearState((x, z), (), ratio))
    return tuple(states)


def transmission_document(raw: Mapping[str, Any], model: Model,
                          plan: ShiftPlan) -> dict[str, Any]:
    """The gearset's model file (as read, ``raw``) with an input shaft, the plan's
    clutches and brakes, and its modes table: a transmission ``powergraph modes`` takes."""
    shaft = next(name for name in ("in", "input", "input_shaft", "shaft_in")
                 if name not in {str(k) for k in raw["components"]})
    frame = model.raw_id(model.frame)
    document = {key: value for key, value in raw.items() if key not in ("ports", "links")}
    document["name"] = f"{raw['name']} with shift elements"
    document["components"] = {**raw["components"], shaft: {"name": "input shaft"}}
    links = list(raw["links"])
    for (kind, member), name in plan.names.items():
        other = [shaft, model.raw_id(member)] if kind == "clutch" else \
            [model.raw_id(member), frame]
        links.append({"type": kind, "name": name, "between": other})
    document["links"] = links
    document["modes"] = plan.modes
    ports = [dict(p) for p in raw["ports"] if p.get("role") == "output"]
    given = [dict(p) for p in raw["ports"] if p.get("role") == "input"]
    entry = given[0] if given else {"role": "input", "speed": "1000 rpm", "power": "1 kW"}
    document["ports"] = [{**entry, "component": shaft}] + ports
    return document


def _check_gearset(model: Model) -> str:
    """The output component of a gearset fit for placing shift elements."""
    if model.shift_elements or model.modes:
        raise UsageError("the model already has shift elements; give the bare gearset")
    if model.buses:
        raise UsageError("a gearset with machines is not supported here")
    outputs = [p.component for p in model.ports if p.role == "output"]
    if len(outputs) != 1 or len(model.ports) > 2:
        raise UsageError("the gearset needs one output port (and at most one input port, "
                         "which moves to the input shaft)")
    dof = degrees_of_freedom(model)
    if dof != 2:
        raise UsageError(f"placing clutches and brakes needs a 2-DOF gearset; this one has "
                         f"{dof} degree(s) of freedom")
    return outputs[0]


def _members(model: Model, output: str) -> list[str]:
    """One component per coaxial body (the levers' nodes), not the frame or the output."""
    from powergraph.analyses.lever import lever_diagram

    taken = {model.frame_body, model.body_of[output]}
    members = []
    for lever in lever_diagram(model).levers:
        for node in lever.nodes:
            if node.body not in taken:
                taken.add(node.body)
                members.append(node.component)
    return members


def _ratio(model: Model, speeds: dict[str, float], output: str) -> float | None:
    try:
        w_out = solve_speeds(model, speeds).speed(output)
    except PowerGraphError:
        return None
    return None if abs(w_out) < STANDSTILL else 1.0 / w_out


def _best_plans(targets: tuple[float, ...], per_target: list[list[GearState]],
                top: int) -> tuple[ShiftPlan, ...]:
    """The ``top`` plans with the fewest elements, then the smallest error; one per set
    of elements."""
    width = len(per_target)
    while _count(per_target) > MAX_COMBINATIONS:
        longest = max(range(width), key=lambda k: len(per_target[k]))
        per_target[longest] = per_target[longest][:-1]
    best: dict[frozenset, tuple] = {}
    for choice in itertools.product(*per_target):
        if len(set(choice)) < width:
            continue            # two gears in one state
        elements = frozenset(e for state in choice for e in state.elements)
        error = max(abs(s.ratio - t) / abs(t) for s, t in zip(choice, targets))
        if elements not in best or error < best[elements][0]:
            best[elements] = (error, choice)
    ranked = sorted(best.items(), key=lambda item: (len(item[0]), item[1][0]))[:top]
    return tuple(ShiftPlan(targets, choice, _names(elements))
                 for elements, (_, choice) in ranked)


def _count(lists: list[list]) -> int:
    total = 1
    for items in lists:
        total *= len(items)
    return total


def _names(elements: frozenset) -> dict[tuple[str, str], str]:
    """C1, C2, ... for the clutches and B1, B2, ... for the brakes, in member order."""
    names = {}
    for kind, letter in (("clutch", "C"), ("brake", "B")):
        for k, member in enumerate(sorted(m for kd, m in elements if kd == kind), start=1):
            names[kind, member] = f"{letter}{k}"
    return names
