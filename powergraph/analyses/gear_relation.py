"""The speed relation of a mode (docs/modes.md): the output's speed as a combination of
the speeds of the mode's driving ports — a ratio for a 1-DOF mode, the lever relation of a
2-DOF one (input split, compound split, two-motor EV).

A train's speeds are linear in the speeds its ports give: with ``D`` of them, every body's
speed is ``Σ_k v_k g_k`` (``v_k`` the motion with the k-th given speed at 1 and the others
at 0). The references are the mode's active ports other than its outputs — inputs first,
then machines, in file order — each kept when its speed is independent of those kept
before (an engine and a machine on one shaft count once), until there are ``D``; the
output's speed is then ``Σ_j c_j w_ref_j``.

Examples
--------
>>> from powergraph.model import load_model
>>> from powergraph.statics.case import TrainCase
>>> point = TrainCase.of(load_model("models/simpson_3speed.yaml"), "2").point()
>>> r = speed_relation(point.result.model)
>>> r.output, [(name, round(c, 6)) for name, c in r.terms], round(r.ratio, 6)
('ports[1]', [('ports[0]', 0.75)], 1.333333)
>>> r.text()
'ratio 1.3333 (ports[0] : ports[1])'
"""
from __future__ import annotations

from typing import Any

import numpy as np

from powergraph.kinematics import solve_speeds
from powergraph.model.spec import Model
from powergraph.records import record

#: A reference is independent of those kept when its row adds rank at this tolerance.
RANK_RTOL = 1e-9


@record
class SpeedRelation:
    """``w_output = Σ coefficient · w_reference`` over ``terms`` ``((name, coefficient),
    ...)``; ``ratio`` the reference's speed over the output's for one reference (None
    otherwise, or when the output does not follow it)."""

    output: str
    terms: tuple[tuple[str, float], ...]

    @property
    def ratio(self) -> float | None:
        if len(self.terms) != 1 or self.terms[0][1] == 0.0:
            return None
        return 1.0 / self.terms[0][1]

    def text(self) -> str:
        """``ratio 7.0047 (MG-B : wheels)`` or ``wheels = 0.3202·MG-A + 0.1427·MG-B``
        (terms that are zero left out)."""
        if self.ratio is not None:
            return f"ratio {self.ratio:.4f} ({self.terms[0][0]} : {self.output})"
        scale = max((abs(c) for _, c in self.terms), default=0.0)
        kept = [(n, c) for n, c in self.terms if abs(c) > 1e-12 * scale]
        if not kept:
            return f"{self.output} = 0"
        text = " + ".join(f"{c:.4g}·{n}" for n, c in kept).replace("+ -", "- ")
        return f"{self.output} = {text}"

    def to_dict(self) -> dict[str, Any]:
        return {"output": self.output, "terms": [{"port": n, "coefficient": c}
                                                 for n, c in self.terms],
                "ratio": self.ratio, "text": self.text()}


def port_name(model: Model, index: int) -> str:
    """A port's name, else ``ports[i]``."""
    return model.ports[index].name or f"ports[{index}]"


def speed_relation(model: Model) -> SpeedRelation | None:
    """The relation of ``model`` (a train in a mode, at its point: a solved case's
    ``result.model``); None without one active output or when its references cannot
    fix the output's speed."""
    outputs = model.outputs
    if len(outputs) != 1:
        return None
    given = list(solve_speeds(model).given)
    ids = [b.id for b in model.bodies]
    basis = []
    for k in range(len(given)):
        unit = {c: float(j == k) for j, c in enumerate(given)}
        speeds = solve_speeds(model, unit).body_speeds
        basis.append([speeds[b] for b in ids])
    basis = np.array(basis)                    # D × bodies
    column = {b: j for j, b in enumerate(ids)}

    def row(component: str) -> np.ndarray:
        return basis[:, column[model.body_of[component]]]

    candidates = [p for p in model.inputs] + [p for p in model.machines
                                               if p.index not in model.inactive]
    kept, rows = [], []
    for port in candidates:
        trial = rows + [row(port.component)]
        if np.linalg.matrix_rank(np.array(trial), tol=RANK_RTOL * max(
                1.0, float(np.abs(trial).max()))) == len(trial):
            kept.append(port.index)
            rows = trial
        if len(kept) == len(given):
            break
    if len(kept) != len(given):
        return None
    coefficients = np.linalg.solve(np.array(rows).T, row(outputs[0].component))
    return SpeedRelation(output=port_name(model, outputs[0].index),
                         terms=tuple((port_name(model, i), float(c) + 0.0)
                                     for i, c in zip(kept, coefficients)))
