"""The power-flow graph of a solved train, seen from the ground or from any body.

Nodes: bodies ("2/3"), elements ("mesh 1-2", "coupling 4-6"), bearings with friction or
drag ("bearing 2-7") and body drags ("drag 6"), the motor(s), the generator(s), "loss",
and "ground" (the world's reaction on the frame, which does work
only when the powers are seen from a moving body). The power from body X into element e
is ``-T_eX · (w_X - w_F)`` with F the observing body (docs/theory.md); losses are the same in
every frame.

A node is known by its kind *and* its name (:class:`Node`): a body whose id is ``motor``
and the motor port are two nodes, whatever the component ids are. Names are unique within
a kind (bodies: :func:`powergraph.model.graph.bodies_of`; elements, bearings: a ``#2``
suffix on the rare clash).

Examples
--------
>>> import powergraph as pg
>>> r = pg.solve(pg.load_model("models/rv40e_wang2021.yaml"))                # doctest: +SKIP
>>> [f for f in r.flows() if f.source_kind == "motor"]              # doctest: +SKIP
[Flow(source='motor', target='1', power=2270.0, source_kind='motor', target_kind='body')]
"""
from __future__ import annotations

from functools import total_ordering
from typing import TYPE_CHECKING

from powergraph.model.graph import unique_name
from powergraph.records import record

if TYPE_CHECKING:
    import networkx as nx

MOTOR, GENERATOR, LOSS, GROUND = "motor", "generator", "loss", "ground"
BODY, FRAME = "body", "frame"
MACHINE, BUS, BATTERY = "machine", "bus", "battery"
#: Every node kind of the flow graph.
KINDS = (BODY, FRAME, "mesh", "coupling", "bearing", "seal", "drag", "churning", MOTOR,
         GENERATOR, LOSS, GROUND, MACHINE, BUS, BATTERY)


@total_ordering
@record
class Node:
    """A node of the flow graph: its ``kind`` (one of :data:`KINDS`) and its ``name``.

    Two nodes are the same only when both agree, so no component id can be mistaken
    for the tool's own nodes. Sorted by name, then kind; ``str(node)`` is the name.

    >>> Node("body", "motor") == Node("motor", "motor"), str(Node("mesh", "mesh 1-2"))
    (False, 'mesh 1-2')
    """

    kind: str
    name: str

    def __str__(self) -> str:
        return self.name

    def __lt__(self, other: "Node") -> bool:
        if not isinstance(other, Node):
            return NotImplemented
        return (self.name, self.kind) < (other.name, other.kind)


@record
class Flow:
    """One arrow of the flow graph: ``power`` W (>= 0) from ``source`` to ``target``.

    ``source``/``target`` are the nodes' names as displayed, ``source_kind``/``target_kind``
    their kinds (:data:`KINDS`); :attr:`source_node`/:attr:`target_node` the nodes.
    """

    source: str
    target: str
    power: float
    source_kind: str = BODY
    target_kind: str = BODY

    @property
    def source_node(self) -> Node:
        return Node(self.source_kind, self.source)

    @property
    def target_node(self) -> Node:
        return Node(self.target_kind, self.target)

    @property
    def key(self) -> tuple[Node, Node]:
        """``(source_node, target_node)``: the arrow's identity."""
        return (self.source_node, self.target_node)

    def to_dict(self) -> dict:
        return {"from": self.source, "to": self.target, "power": self.power,
                "from_kind": self.source_kind, "to_kind": self.target_kind}


def body_node(result: "PowerFlowResult", body: str) -> Node:
    """The node of body ``body`` (kind ``frame`` for the housing)."""
    return Node(FRAME if body == result.model.frame_body else BODY, body)


def element_nodes(result: "PowerFlowResult") -> dict[int, Node]:
    """Node of each element by link index: ``mesh 1-2`` or ``coupling 4-6`` (ids as in
    the file), ``#2``... added when two elements of a kind would share a name."""
    raw = result.model.raw_id
    taken: dict[str, set[str]] = {}
    nodes = {}
    for element in result.elements:
        names = taken.setdefault(element.kind, set())
        name = unique_name(f"{element.kind} {raw(element.a)}-{raw(element.b)}", names)
        names.add(name)
        nodes[element.link] = Node(element.kind, name)
    return nodes


def element_node(result: "PowerFlowResult", element: "ElementFlow") -> str:
    """Node name of an element: ``mesh 1-2`` or ``coupling 4-6`` (ids as in the file)."""
    return element_nodes(result)[element.link].name


def port_node(result: "PowerFlowResult", component: str, role: str) -> Node:
    """The port's node: kind ``motor``/``generator``, named so, or ``motor 1`` (the
    component's id) when the train has several of that role."""
    base = MOTOR if role == "input" else GENERATOR
    ports = result.model.inputs if role == "input" else result.model.outputs
    return Node(base, base if len(ports) == 1 else f"{base} {result.model.raw_id(component)}")


def _arrow(source: Node, target: Node, power: float) -> Flow:
    return Flow(source.name, target.name, power, source.kind, target.kind)


def _oriented(source: Node, target: Node, power: float) -> Flow:
    power = power + 0.0  # no -0.0 in reports
    return _arrow(source, target, power) if power >= 0 else _arrow(target, source, -power)


def flow_edges(result: "PowerFlowResult", frame: str | None = None) -> list[Flow]:
    """Every arrow of the flow graph, seen from the body of component ``frame``.

    ``frame=None`` (or a component of the frame body) gives the actual powers.
    Zero-power arrows are kept (frame links carry 0 power: the paper's principle 1).
    """
    kin, model = result.kinematics, result.model
    w_f = 0.0 if frame is None else kin.speed(str(frame))
    moving_view = frame is not None and model.body_of[str(frame)] != model.frame_body
    loss = Node(LOSS, LOSS)
    edges: list[Flow] = []
    for port in model.ports:
        if port.role == MACHINE or port.index in model.inactive:
            continue
        body = model.body_of[port.component]
        power = result.port_torque(port.index) * (kin.body_speeds[body] - w_f)
        node, at = port_node(result, port.component, port.role), body_node(result, body)
        edges.append(_oriented(node, at, power) if port.role == "input"
                     else _oriented(at, node, -power))
    if moving_view:
        torque = result.external_torques[model.frame_body]
        if result.machines:     # the stators sit on the housing: the ground holds them too
            torque = torque + sum(m.torque for m in result.machines)
        edges.append(_oriented(Node(GROUND, GROUND), body_node(result, model.frame_body),
                               torque * (0.0 - w_f)))
    nodes = element_nodes(result)
    for element in result.elements:
        node = nodes[element.link]
        for body, torque in element.torques.items():
            edges.append(_oriented(body_node(result, body), node,
                                   -torque * (kin.body_speeds[body] - w_f)))
        if element.loss > 0 or element.efficiency < 1:
            edges.append(_arrow(node, loss, element.loss))
    for bearing in result.bearings:     # docs/losses.md: a torque pair opposing Δω
        node = Node(bearing.kind, bearing.node)
        for body, torque in bearing.torques.items():
            edges.append(_oriented(body_node(result, body), node,
                                   -torque * (kin.body_speeds[body] - w_f)))
        edges.append(_arrow(node, loss, bearing.loss))
    return edges + machine_edges(result, w_f)


def machine_edges(result: "PowerFlowResult", w_f: float = 0.0) -> list[Flow]:
    """The arrows of the machines and buses (docs/hybrid.md): machine ↔ its body
    (mechanical), bus ↔ machine and battery ↔ bus (electrical), machine → loss; seen
    from a moving body, the stator's reaction on the housing too."""
    model, edges, loss = result.model, [], Node(LOSS, LOSS)
    for machine in result.machines:
        if not machine.active:
            continue
        node, bus = Node(MACHINE, machine.name), Node(BUS, machine.bus)
        body = model.body_of[machine.component]
        edges.append(_oriented(node, body_node(result, body),
                               machine.torque * (machine.speed - w_f)))
        if w_f != 0.0:          # its stator's reaction on the housing, seen moving
            edges.append(_oriented(node, body_node(result, model.frame_body),
                                   machine.torque * w_f))
        edges.append(_oriented(bus, node, machine.electrical_power))
        edges.append(_arrow(node, loss, machine.loss))
    for name, flow in result.buses.items():
        edges.append(_oriented(Node(BATTERY, f"battery {name}"), Node(BUS, name),
                               flow.battery_power))
    return edges


def flow_graph(result: "PowerFlowResult", frame: str | None = None) -> "nx.DiGraph":
    """The flow edges as a networkx DiGraph keyed by :class:`Node`, with ``power`` on each
    edge and ``kind`` and ``name`` on each node (bodies carry ``members``, elements,
    bearings and drags their ``link``)."""
    import networkx as nx

    graph = nx.DiGraph(frame=frame)
    for body in result.model.bodies:
        node = body_node(result, body.id)
        graph.add_node(node, kind=node.kind, name=node.name, members=body.members)
    for link, node in element_nodes(result).items():
        graph.add_node(node, kind=node.kind, name=node.name, link=link)
    for bearing in result.bearings:
        graph.add_node(Node(bearing.kind, bearing.node), kind=bearing.kind, name=bearing.node,
                       link=bearing.link)
    for edge in flow_edges(result, frame):
        for node in edge.key:
            if node not in graph:
                graph.add_node(node, kind=node.kind, name=node.name)
        graph.add_edge(*edge.key, power=edge.power)
    return graph


def circulating_power(edges: list[Flow], tolerance: float = 1e-9) -> float:
    """Largest, over directed cycles, of the smallest flow along the cycle (0 if none).

    Adds arrows from the strongest down; the first one that closes a directed cycle
    bounds every cycle through it, so its power is the answer (a bottleneck cycle).

    >>> circulating_power([Flow("a", "b", 5.0), Flow("b", "a", 2.0), Flow("b", "c", 9.0)])
    2.0
    """
    largest = max((e.power for e in edges), default=0.0)
    successors: dict[Node, set[Node]] = {}
    for edge in sorted(edges, key=lambda e: -e.power):
        if edge.power <= tolerance * max(1.0, largest):
            break
        source, target = edge.key
        if _reaches(successors, target, source):
            return edge.power
        successors.setdefault(source, set()).add(target)
    return 0.0


def _reaches(successors: dict[Node, set[Node]], start: Node, goal: Node) -> bool:
    """Depth-first search (kept here so a solve need not import networkx)."""
    seen, stack = {start}, [start]
    while stack:
        node = stack.pop()
        if node == goal:
            return True
        for nxt in successors.get(node, ()):
            if nxt not in seen:
                seen.add(nxt)
                stack.append(nxt)
    return False


def split_powers(edges: list[Flow], tolerance: float = 1e-9) -> dict[Node, dict[Node, float]]:
    """Nodes that send power into several others: ``{node: {target: power}}`` (keys are
    :class:`Node`; ``str(node)`` is its name).

    >>> split = split_powers([Flow("a", "b", 5.0), Flow("a", "c", 2.0), Flow("b", "c", 9.0)])
    >>> {str(n): {str(t): p for t, p in to.items()} for n, to in split.items()}
    {'a': {'b': 5.0, 'c': 2.0}}
    """
    largest = max((e.power for e in edges), default=0.0)
    out: dict[Node, dict[Node, float]] = {}
    for edge in edges:
        if edge.power > tolerance * max(1.0, largest) and edge.target_kind != LOSS:
            out.setdefault(edge.source_node, {})[edge.target_node] = edge.power
    return {node: targets for node, targets in out.items() if len(targets) > 1}
