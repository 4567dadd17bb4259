"""The model as a graph: rigid bodies from ``fixed`` links, and a networkx view.

Examples
--------
>>> from powergraph.model import load_model
>>> model = load_model("models/rv40e_wang2021.yaml")                   # doctest: +SKIP
>>> [b.id for b in model.bodies]                              # doctest: +SKIP
['0/5', '1', '2/3', '4', '6/7']
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Collection, Mapping

from powergraph.errors import ModelError
from powergraph.model.spec_parts import Body, Component, Link

if TYPE_CHECKING:
    import networkx as nx

# ``Model`` is named as text, not imported: ``Model.in_mode`` (powergraph.model.spec) reaches
# this module through powergraph.model.modes.


def bodies_of(components: Mapping[str, Component],
              links: tuple[Link, ...]) -> tuple[tuple[Body, ...], dict[str, str]]:
    """Contract ``fixed`` links: each connected set of components is one body.

    Bodies are listed by the file order of their first component. A body of one
    component is named by that component's id; a body of several by their ids joined
    with ``/`` in file order (the paper's "2/3"), made unique by :func:`unique_name` when
    that name is already a component's id or another body's (``F/R #2``).
    """
    # A small union-find rather than networkx here: `powergraph solve` must start fast and
    # networkx costs ~0.2 s to import; the full graph view is `to_networkx` below.
    parent = {cid: cid for cid in components}

    def root(cid: str) -> str:
        while parent[cid] != cid:
            parent[cid] = parent[parent[cid]]
            cid = parent[cid]
        return cid

    for link in links:
        if link.type == "fixed":
            parent[root(link.between[0])] = root(link.between[1])
    grouped: dict[str, list[str]] = {}
    for cid in components:  # file order, so members and bodies come out in file order
        grouped.setdefault(root(cid), []).append(cid)
    taken = set(components)
    bodies = []
    for group in grouped.values():
        name = group[0]
        if len(group) > 1:
            name = unique_name("/".join(group), taken)
            taken.add(name)
        bodies.append(Body(id=name, members=tuple(group),
                           is_frame=any(components[c].is_frame for c in group)))
    bodies = tuple(bodies)
    body_of = {cid: body.id for body in bodies for cid in body.members}
    return bodies, body_of


def unique_name(candidate: str, taken: Collection[str]) -> str:
    """``candidate``, or ``candidate #2``, ``#3``... : the first not in ``taken``.

    >>> unique_name("F/R", {"F", "R", "F/R"})
    'F/R #2'
    """
    name, number = candidate, 2
    while name in taken:
        name, number = f"{candidate} #{number}", number + 1
    return name


def check_topology(model: Model) -> None:
    """Checks that need bodies: a mesh or coupling inside one rigid body is an error, and
    so is an active port on the frame's body. Several ports may share a rigid body (an
    engine and a machine on one shaft): the solve checks that the speeds they give agree
    and that their loads are determined (docs/modes.md)."""
    for link in model.links:
        if link.type not in ("mesh", "coupling"):
            continue
        a, b = (model.body_of[x] for x in link.between)
        if a == b:
            raise ModelError(f"{link.between[0]!r} and {link.between[1]!r} are one rigid body "
                             "(joined by fixed links), so they cannot mesh or couple",
                             f"{link.path}.between")
    for port in model.ports:
        if port.index in model.inactive:
            continue
        if model.body_of[port.component] == model.frame_body:
            raise ModelError(f"component {port.component!r} is fixed to the frame, so it cannot "
                             "be a port", f"{port.path}.component")


def shared_port_bodies(model: Model) -> dict[str, tuple[int, ...]]:
    """``{body: port indices}`` of the bodies that carry more than one active port.

    >>> from powergraph.model import model_from_dict
    >>> m = model_from_dict({"name": "p1", "components": {0: {"role": "frame"},
    ...     "e": {}, "a": {"teeth": 20}, "w": {"teeth": 40}},
    ...     "links": [{"type": "fixed", "between": ["e", "a"]},
    ...               {"type": "mesh", "between": ["a", "w"]}],
    ...     "ports": [{"component": "e", "role": "input", "speed": 10, "power": 100},
    ...               {"component": "a", "role": "input", "power": 50},
    ...               {"component": "w", "role": "output"}]})
    >>> shared_port_bodies(m)
    {'e/a': (0, 1)}
    """
    found: dict[str, list[int]] = {}
    for port in model.ports:
        if port.index not in model.inactive:
            found.setdefault(model.body_of[port.component], []).append(port.index)
    return {body: tuple(ports) for body, ports in found.items() if len(ports) > 1}


def to_networkx(model: Model) -> "nx.MultiGraph":
    """The model as a networkx MultiGraph (components are nodes, links are edges).

    Node attributes are the component's fields plus ``body``; edge attributes are the
    link's fields (``type``, ``carrier``, ``efficiency``, ``ratio``), keyed by link index.

    Examples
    --------
    >>> from powergraph.model import model_from_dict
    >>> m = model_from_dict({"name": "pair",
    ...     "components": {0: {"role": "frame"}, 1: {"teeth": 20}, 2: {"teeth": 40}},
    ...     "links": [{"type": "mesh", "between": [1, 2], "carrier": 0}],
    ...     "ports": [{"component": 1, "role": "input"}, {"component": 2, "role": "output"}]})
    >>> g = to_networkx(m)
    >>> g.number_of_nodes(), g.edges[("1", "2", 0)]["carrier"]
    (3, '0')
    """
    import networkx as nx

    graph = nx.MultiGraph(name=model.name)
    for cid, comp in model.components.items():
        graph.add_node(cid, body=model.body_of[cid], teeth=comp.teeth, internal=comp.internal,
                       count=comp.count, role=comp.role, name=comp.name)
    for link in model.links:
        graph.add_edge(*link.between, key=link.index, type=link.type, carrier=link.carrier,
                       efficiency=link.efficiency, ratio=link.ratio)
    return graph
