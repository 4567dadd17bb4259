"""What a power-flow diagram shows: the flows seen from one body, with their labels.

A :class:`FlowView` is the drawing-independent content of one diagram (the paper's
Figs. 5-10): every arrow of the flow graph with its power, the kind of every node, the
power the shares are taken of, and the arrows that lie on a circulating loop. It is
built from a virtual-power result (``powergraph.solve``) or from any result that lists
its flows as ``[{from, to, power}]`` in ``to_dict()["flows"]`` (``--method wang2021``).

Examples
--------
>>> import powergraph as pg
>>> result = pg.solve(pg.load_model("models/rv40e_wang2021.yaml"))      # doctest: +SKIP
>>> view = flow_view(result, frame="3")                         # doctest: +SKIP
>>> view.title                                                  # doctest: +SKIP
'RV-40E: virtual powers seen from 2/3 (held as the frame)'
>>> format_power(2270.0), format_share(2063.26, 2270.0)
('2.27 kW', '90.9 %')
"""
from __future__ import annotations

from dataclasses import field
from typing import Any, Iterable, Mapping

import networkx as nx

from powergraph.errors import UsageError
from powergraph.plot.layout.nodes import NodeMap
from powergraph.records import record
from powergraph.statics.flow import (BODY, FRAME, GENERATOR, GROUND, KINDS, LOSS, MOTOR, Flow,
                                     Node, circulating_power, port_node)
from powergraph.format import format_power, format_share  # noqa: F401  (re-exported)


@record
class FlowView:
    """The content of one power-flow diagram (no geometry).

    Attributes
    ----------
    name : str
        Model name.
    frame_body : str or None
        Body whose frame the powers are seen from; None for the actual powers.
    flows : tuple of Flow
        Every arrow, in the result's order (zero-power arrows included).
    kinds : NodeMap
        :class:`~powergraph.statics.flow.Node` -> the kind drawn (one of ``KINDS``; the
        held body is drawn as ``frame``). A node's name may stand for it when unambiguous.
    held : str or None
        The body drawn as the frame: the observer in a moving view, else the housing.
    input_power : float
        The actual input power P; every share is ``power / P``.
    circulating : float
        Circulating power of the flows shown (W, 0 when they have no directed cycle).
    loop_edges : frozenset of (Node, Node)
        Arrows on a directed cycle of positive power (``Flow.key``).
    method : str
        Method of the result ("virtual-power", "wang2021", ...).
    reference : tuple of Flow
        The actual flows, when this view is from a moving body: a layout hint that keeps
        members idle in this view (zero power) in their actual order.
    labels : NodeMap
        Node -> the text drawn for it, when that is not its name: the input and output
        ports (nodes of kind ``motor``/``generator``, named so) are captioned with the
        port's name, else with their role (``input``, ``output``; ``input 1``... when the
        train has several). See :meth:`text`.
    """

    name: str
    frame_body: str | None
    flows: tuple[Flow, ...]
    kinds: Mapping[Node, str]
    held: str | None
    input_power: float
    circulating: float
    loop_edges: frozenset
    method: str = "virtual-power"
    reference: tuple[Flow, ...] = ()
    labels: Mapping[Node, str] = field(default_factory=NodeMap)

    @property
    def title(self) -> str:
        """Whose frame the powers are seen from."""
        if self.frame_body is None:
            return f"{self.name}: actual powers (ground frame)"
        return f"{self.name}: virtual powers seen from {self.frame_body} (held as the frame)"

    @property
    def largest(self) -> float:
        return max((f.power for f in self.flows), default=0.0)

    def is_zero(self, flow: Flow) -> bool:
        """A flow too small to draw as carrying power (frame links, rounding noise)."""
        return flow.power <= 1e-9 * max(self.largest, 1e-300)

    def text(self, node: Node) -> str:
        """What a reader sees for ``node``: its label (a port's name), else its name."""
        return self.labels.get(node, node.name)

    def label(self, flow: Flow) -> str:
        """``'2.06 kW\\n90.9 %'``: the power and its share of the input power."""
        power = 0.0 if self.is_zero(flow) else flow.power
        return f"{format_power(power)}\n{format_share(power, self.input_power)}"


def flow_view(result: Any, frame: str | int | None = None) -> FlowView:
    """The diagram content of ``result`` seen from the body of component ``frame``.

    Parameters
    ----------
    result : PowerFlowResult or a result with ``to_dict()["flows"]``
    frame : component id (or body id such as ``"2/3"``), optional
        None, or any member of the housing, gives the actual powers.

    Raises
    ------
    UsageError
        ``frame`` names no component or body, or the result has no view from a frame.
    """
    model = getattr(result, "model", None)
    component = _frame_component(model, frame)
    frame_body = None
    if component is not None and model is not None and \
            model.body_of[component] != model.frame_body:
        frame_body = model.body_of[component]
    flows = _flows(result, component)
    kinds = _kinds(result, model, flows, component)
    held = frame_body if frame_body is not None else (model.frame_body if model else None)
    if any(n.kind in (BODY, FRAME) and n.name == held for n in kinds):
        kinds = {n: (FRAME if n.kind in (BODY, FRAME) and n.name == held
                     else (BODY if k == FRAME else k)) for n, k in kinds.items()}
    return FlowView(name=_name(result, model), frame_body=frame_body, flows=tuple(flows),
                    kinds=NodeMap(kinds), held=held, input_power=_input_power(result, flows),
                    circulating=circulating_power(list(flows)),
                    loop_edges=loop_edges(flows),
                    method=str(getattr(result, "method", "virtual-power")),
                    reference=tuple(_flows(result, None)) if frame_body is not None else (),
                    labels=NodeMap(port_labels(result, model, kinds)))


#: The role a port node's kind stands for (what an unnamed port is called in a drawing).
ROLES = {MOTOR: "input", GENERATOR: "output"}


def port_labels(result: Any, model: Any, nodes: Iterable[Node]) -> dict[Node, str]:
    """The caption of every input and output port node among ``nodes``: the port's
    ``name``, else its role (``input``/``output``, with the component's id when the
    train has several ports of that role, as the node's name has).

    >>> labels = port_labels(None, None, [Node("motor", "motor"), Node("body", "motor"),
    ...                                   Node("generator", "generator 6")])
    >>> sorted(labels.values())
    ['input', 'output 6']
    """
    nodes = [n for n in nodes if n.kind in ROLES]
    named: dict[Node, str] = {}
    if model is not None and nodes:
        for port in model.ports:
            if port.role in ("input", "output") and port.name:
                named[port_node(result, port.component, port.role)] = str(port.name)
    return {n: named.get(n) or _role_text(n) for n in nodes}


def _role_text(node: Node) -> str:
    """``motor`` -> ``input``, ``generator 6`` -> ``output 6``; another name as it is."""
    if node.name == node.kind or node.name.startswith(node.kind + " "):
        return ROLES[node.kind] + node.name[len(node.kind):]
    return node.name


def loop_edges(flows: tuple[Flow, ...] | list[Flow], tolerance: float = 1e-9) -> frozenset:
    """Arrows of positive power that lie on a directed cycle (circulating power).

    >>> edges = loop_edges([Flow("a", "b", 5.0), Flow("b", "a", 2.0), Flow("b", "c", 9.0)])
    >>> sorted((str(a), str(b)) for a, b in edges)
    [('a', 'b'), ('b', 'a')]
    """
    largest = max((f.power for f in flows), default=0.0)
    graph = nx.DiGraph()
    graph.add_edges_from(f.key for f in flows
                         if f.power > tolerance * max(largest, 1e-300))
    loops = [c for c in nx.strongly_connected_components(graph) if len(c) > 1]
    return frozenset((u, v) for c in loops for u, v in graph.subgraph(c).edges)


def _frame_component(model, frame) -> str | None:
    if frame is None:
        return None
    key = str(frame)
    if model is None:
        raise UsageError(f"--frame {frame}: this result has no model to take a frame from")
    if key in model.components:
        return key
    for body in model.bodies:
        if body.id == key:
            return body.members[0]
    known = ", ".join(str(model.raw_id(c)) for c in model.components)
    raise UsageError(f"--frame {frame}: unknown component {key!r} (components: {known})")


def _flows(result, component: str | None) -> list[Flow]:
    """The flows of ``result`` seen from ``component``. A result whose ``flows()`` takes
    no frame (the paper's method) is seen from a frame through its ``realisation``
    (the virtual-power result that carries its losses), if it has one."""
    source = result
    if component is not None:
        try:
            items = result.flows(component)
        except TypeError:
            source = getattr(result, "realisation", None)
            if not callable(getattr(source, "flows", None)):
                raise UsageError("this result cannot be seen from another frame "
                                 "(draw it without --frame)") from None
            items = source.flows(component)
    elif callable(getattr(result, "flows", None)):
        items = result.flows()
    else:
        items = result.to_dict()["flows"]
    return [item if isinstance(item, Flow) else _flow_from_dict(item) for item in items]


def _flow_from_dict(item: Mapping) -> Flow:
    """A JSON flow; one written without ``from_kind``/``to_kind`` (older output) has its
    kinds guessed from the names."""
    source, target = str(item["from"]), str(item["to"])
    return Flow(source, target, float(item["power"]),
                str(item.get("from_kind") or _kind_from_name(source)),
                str(item.get("to_kind") or _kind_from_name(target)))


def _kinds(result, model, flows, component) -> dict[Node, str]:
    kinds: dict[Node, str] = {}
    if callable(getattr(result, "flow_graph", None)):
        graph = result.flow_graph(component) if component is not None else result.flow_graph()
        kinds = {n: d.get("kind", n.kind) for n, d in graph.nodes(data=True)}
    elif model is not None:
        kinds = {Node(FRAME if b.is_frame else BODY, b.id): (FRAME if b.is_frame else BODY)
                 for b in model.bodies}
    for flow in flows:
        for node in flow.key:
            kinds.setdefault(node, node.kind)
    return {n: (k if k in KINDS else BODY) for n, k in kinds.items()}


def _kind_from_name(node: str) -> str:
    """The kind of a node named in a flow list without kinds (ambiguous by nature)."""
    head = node.split(" ")[0]
    if head in (MOTOR, GENERATOR) or node in (LOSS, GROUND):
        return head
    if head in ("mesh", "coupling", "bearing", "seal", "drag", "churning") and " " in node:
        return head
    return BODY


def _name(result, model) -> str:
    name = getattr(result, "name", None) or (model.name if model is not None else None)
    return str(name) if name else "gear train"


def _input_power(result, flows: list[Flow]) -> float:
    power = getattr(result, "input_power", None)
    if power is None and callable(getattr(result, "to_dict", None)):
        power = result.to_dict().get("input_power")
    if power is None:
        power = sum(f.power for f in flows if f.source_kind == MOTOR)
    return float(power)
