"""Model documents for enumerated graphs: a frame, ports and placeholder tooth numbers.

An enumerated graph is a kinematic chain; to solve it, powergraph needs a frame, input(s)
and an output. :func:`model_document` takes them among the links of the main axis (the
axis with most links; frame, input and output of a planetary train are coaxial), else
among the links that share an axis with the frame, and keeps the first choice whose
speeds are fixed by the inputs with every port turning, and whose loads follow from the one
input power given (a port choice can leave a part of a 2-DOF train unloaded). Tooth numbers are
placeholders (distinct, external); ``powergraph formula`` gives the ratio in symbols.
"""
from __future__ import annotations

from itertools import permutations
from typing import Any

from powergraph.analyses.synthesis.graph import TrainGraph
from powergraph.errors import PowerGraphError

PLACEHOLDER_NOTE = ("tooth numbers are placeholders (distinct external gears), not a design; "
                    "`powergraph formula` gives the ratio in symbols")


def placeholder_teeth(train: TrainGraph) -> dict[tuple[int, int], int]:
    """Distinct tooth numbers for every side of every gear pair: 17, 19, 23, ... (primes).

    Examples
    --------
    >>> placeholder_teeth(TrainGraph(3, ((0, 1, 0), (0, 2, 1)), ((1, 2, 0),)))
    {(0, 0): 17, (0, 1): 19}
    """
    primes = [p for p in range(17, 400) if all(p % d for d in range(2, int(p ** 0.5) + 1))]
    return {(k, s): primes[2 * k + s] for k in range(len(train.gear_pairs)) for s in (0, 1)}


def component_names(train: TrainGraph, frame: int) -> dict[str, str]:
    """A name per link and gear from the graph alone: a link on the main axis that carries
    a gear pair is a ``carrier``, another one ``central`` (sun or ring: the placeholder
    teeth do not decide), a link off the main axis a ``planet``; a gear is named after
    its link (``planet gear L2``); the frame is marked ``(fixed)``.

    >>> g = TrainGraph(4, ((0, 1, 0), (0, 2, 0), (0, 3, 1)), ((1, 3, 0), (2, 3, 0)))
    >>> component_names(g, 0)["L3"], component_names(g, 0)["g0b"]
    ('planet L3', 'planet gear L3')
    """
    from powergraph.analyses.synthesis.enumerate import axes_of

    main = max(axes_of(train), key=len)
    carriers = {c for _, _, c in train.gear_pairs}
    roles = {n: ("planet" if n not in main else "carrier" if n in carriers else "central")
             for n in range(train.links)}
    names = {f"L{n}": f"{role} L{n}" + (" (fixed)" if n == frame else "")
             for n, role in roles.items()}
    for k, (u, v, _) in enumerate(train.gear_pairs):
        for side, link in enumerate((u, v)):
            names[f"g{k}{'ab'[side]}"] = f"{roles[link]} gear L{link}"
    return names


def model_document(train: TrainGraph, teeth: dict[tuple[int, int], int] | None = None,
                   mesh_efficiency: float = 1.0) -> dict[str, Any]:
    """A model document for ``train`` (:meth:`TrainGraph.to_model_dict`) that solves.

    Raises
    ------
    PowerGraphError
        When no frame and ports among the links give a train that moves (not expected for
        an enumerated graph).

    Examples
    --------
    >>> from powergraph.model import model_from_dict
    >>> g = TrainGraph(4, ((0, 1, 0), (0, 2, 0), (0, 3, 1)), ((1, 3, 0), (2, 3, 0)))
    >>> doc = model_document(g)
    >>> [p["component"] for p in doc["ports"]]
    ['L1', 'L2']
    >>> model_from_dict(doc).frame
    'L0'
    """
    from powergraph.analyses.synthesis.enumerate import axes_of

    teeth = teeth or placeholder_teeth(train)
    axes = sorted(axes_of(train), key=lambda a: (-len(a), sorted(a)))
    for frame in sorted(range(train.links), key=lambda n: (n not in axes[0], n)):
        coaxial = {x for a in axes if frame in a for x in a} - {frame}
        order = sorted(coaxial, key=lambda n: (n not in axes[0], n))
        order += [n for n in range(train.links) if n not in coaxial and n != frame]
        for ports in permutations(order, train.dof + 1):
            doc = train.to_model_dict(frame=frame, inputs=ports[:-1], outputs=ports[-1:],
                                      teeth=teeth, mesh_efficiency=mesh_efficiency,
                                      name=train.name, names=component_names(train, frame))
            doc["description"] = (f"{train.name or 'train'}: {train.dof}-DOF graph of "
                                  f"{train.links} links; {PLACEHOLDER_NOTE}")
            if _moves(doc, train.dof):
                return doc
    raise PowerGraphError(f"{train.name}: no frame and ports make this train move")


def _moves(doc: dict[str, Any], dof: int) -> bool:
    """The inputs fix the speeds, every port turns, and the one given power fixes the loads."""
    from powergraph.errors import ModelError
    from powergraph.kinematics import solve_speeds
    from powergraph.kinematics.speeds import degrees_of_freedom
    from powergraph.model import model_from_dict
    from powergraph.statics import solve

    model = model_from_dict(doc)
    if degrees_of_freedom(model) != dof:
        return False
    try:
        speeds = solve_speeds(model)
        if not all(abs(speeds.speed(p.component)) > 1e-9 for p in model.ports):
            return False
        solve(model)
    except ModelError:
        return False
    return True
