"""The power-flow graph of a solved train, seen from the ground or from any body.

Nodes: bodies ("2/3"), elements ("mesh 1-2", "coupling 4-6"), bearings with friction or
drag ("bearing 2-7") and body drags ("drag 6"), the motor(s), the generator(s), "loss",
and "ground" (the world's reaction on the frame, which does work
only when the powers are seen from a moving body). The power from body X into element e
is ``-T_eX · (w_X - w_F)`` with F the observing body (docs/theory.md); losses are the same in
every frame.

Examples
--------
>>> import powergraph as pg
>>> r = pg.solve(pg.load_model("models/rv40e_wang2021.yaml"))                # doctest: +SKIP
>>> [f for f in r.flows() if f.source == "motor"]                   # doctest: +SKIP
[Flow(source='motor', target='1', power=2270.0)]
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import networkx as nx

    from powergraph.statics.result import ElementFlow, PowerFlowResult

MOTOR, GENERATOR, LOSS, GROUND = "motor", "generator", "loss", "ground"


@dataclass(frozen=True)
class Flow:
    """One arrow of the flow graph: ``power`` W (>= 0) from ``source`` to ``target``."""

    source: str
    target: str
    power: float

    def to_dict(self) -> dict:
        return {"from": self.source, "to": self.target, "power": self.power}


def element_node(result: "PowerFlowResult", element: "ElementFlow") -> str:
    """Node name of an element: ``mesh 1-2`` or ``coupling 4-6`` (ids as in the file)."""
    raw = result.model.raw_id
    return f"{element.kind} {raw(element.a)}-{raw(element.b)}"


def port_node(result: "PowerFlowResult", component: str, role: str) -> str:
    """``motor``/``generator``, or ``motor 1`` when the train has several of that role."""
    base = MOTOR if role == "input" else GENERATOR
    ports = result.model.inputs if role == "input" else result.model.outputs
    return base if len(ports) == 1 else f"{base} {result.model.raw_id(component)}"


def _oriented(source: str, target: str, power: float) -> Flow:
    power = power + 0.0  # no -0.0 in reports
    return Flow(source, target, power) if power >= 0 else Flow(target, source, -power)


def flow_edges(result: "PowerFlowResult", frame: str | None = None) -> list[Flow]:
    """Every arrow of the flow graph, seen from the body of component ``frame``.

    ``frame=None`` (or a component of the frame body) gives the actual powers.
    Zero-power arrows are kept (frame links carry 0 power: the paper's principle 1).
    """
    kin, model = result.kinematics, result.model
    w_f = 0.0 if frame is None else kin.speed(str(frame))
    moving_view = frame is not None and model.body_of[str(frame)] != model.frame_body
    edges: list[Flow] = []
    for port in model.ports:
        body = model.body_of[port.component]
        power = result.external_torques.get(body, 0.0) * (kin.body_speeds[body] - w_f)
        node = port_node(result, port.component, port.role)
        edges.append(_oriented(node, body, power) if port.role == "input"
                     else _oriented(body, node, -power))
    if moving_view:
        torque = result.external_torques[model.frame_body]
        edges.append(_oriented(GROUND, model.frame_body, torque * (0.0 - w_f)))
    for element in result.elements:
        node = element_node(result, element)
        for body, torque in element.torques.items():
            edges.append(_oriented(body, node, -torque * (kin.body_speeds[body] - w_f)))
        if element.loss > 0 or element.efficiency < 1:
            edges.append(Flow(node, LOSS, element.loss))
    for bearing in result.bearings:     # docs/losses.md: a torque pair opposing Δω
        for body, torque in bearing.torques.items():
            edges.append(_oriented(body, bearing.node, -torque * (kin.body_speeds[body] - w_f)))
        edges.append(Flow(bearing.node, LOSS, bearing.loss))
    return edges


def flow_graph(result: "PowerFlowResult", frame: str | None = None) -> "nx.DiGraph":
    """The flow edges as a networkx DiGraph with ``power`` on each edge and a ``kind`` on
    each node (body, frame, mesh, coupling, bearing, drag, motor, generator, loss,
    ground)."""
    import networkx as nx

    graph = nx.DiGraph(frame=frame)
    model = result.model
    for body in model.bodies:
        graph.add_node(body.id, kind="frame" if body.is_frame else "body",
                       members=body.members)
    for element in result.elements:
        graph.add_node(element_node(result, element), kind=element.kind, link=element.link)
    for bearing in result.bearings:
        graph.add_node(bearing.node, kind=bearing.kind, link=bearing.link)
    for edge in flow_edges(result, frame):
        for node in (edge.source, edge.target):
            if node not in graph:
                graph.add_node(node, kind=node.split(" ")[0])
        graph.add_edge(edge.source, edge.target, power=edge.power)
    return graph


def circulating_power(edges: list[Flow], tolerance: float = 1e-9) -> float:
    """Largest, over directed cycles, of the smallest flow along the cycle (0 if none).

    Adds arrows from the strongest down; the first one that closes a directed cycle
    bounds every cycle through it, so its power is the answer (a bottleneck cycle).

    >>> circulating_power([Flow("a", "b", 5.0), Flow("b", "a", 2.0), Flow("b", "c", 9.0)])
    2.0
    """
    largest = max((e.power for e in edges), default=0.0)
    successors: dict[str, set[str]] = {}
    for edge in sorted(edges, key=lambda e: -e.power):
        if edge.power <= tolerance * max(1.0, largest):
            break
        if _reaches(successors, edge.target, edge.source):
            return edge.power
        successors.setdefault(edge.source, set()).add(edge.target)
    return 0.0


def _reaches(successors: dict[str, set[str]], start: str, goal: str) -> bool:
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


def split_powers(edges: list[Flow], tolerance: float = 1e-9) -> dict[str, dict[str, float]]:
    """Nodes that send power into several others: ``{node: {target: power}}``."""
    largest = max((e.power for e in edges), default=0.0)
    out: dict[str, dict[str, float]] = {}
    for edge in edges:
        if edge.power > tolerance * max(1.0, largest) and edge.target != LOSS:
            out.setdefault(edge.source, {})[edge.target] = edge.power
    return {node: targets for node, targets in out.items() if len(targets) > 1}
