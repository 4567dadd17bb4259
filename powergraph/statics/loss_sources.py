"""Loss sources: every loss of a train's case, described once per model.

Each loss of a train is a :class:`LossSource`: its kind, its YAML path, its label, the two
members it acts between, its instances, its laws, and how the solve applies it
(``applied``):

- ``"element"``: a mesh, or a coupling with an efficiency below 1, loses through its
  element's factor in the torque balance (its basic efficiency, or a ``friction:``/``pins:``
  law of the tooth load, in ``friction``);
- ``"torque"``: a torque ``M >= 0`` between two bodies opposing their relative rotation
  ``Δω``, losing ``M·|Δω|`` — a bearing's friction and drag, a component's drag against
  the housing, an open clutch's drag (an open shift element is a bearing carrying its
  drag), or any registered kind. Its laws have a vectorised ``torque(x)`` (N·m per
  instance): ``friction.torque(radial load)`` and ``drag.torque(relative speed)``;
  ``loaded_by`` names the meshes whose tooth forces load its friction;
- ``"machine"``: an electric machine's loss, set by the bus balance.

Every evaluator takes the same list (:func:`loss_sources`): the single solve's bearing
iteration and the batched efficiency grid (the ``"torque"`` sources,
:func:`torque_sources`), the report's loss breakdown, the flow graph, the duty cycle's
energy per element and :func:`powergraph.testing.assert_conservation` (each source's loss
in a result, :func:`losses`), and the methods that read plain efficiencies and so refuse
load-dependent laws (:func:`powergraph.statics.friction.loss_block_places`).

A new loss type is one module with a builder — ``builder(model) -> iterable of
LossSource`` — and one line registering it (:data:`BUILDERS`, or :func:`registered` for a
builder that lives outside the package, e.g. in a test).

Examples
--------
>>> from powergraph.model import load_model
>>> sources = loss_sources(load_model("models/rv40e.yaml"))
>>> [(s.kind, s.path, s.node) for s in sources][:4]  # doctest: +NORMALIZE_WHITESPACE
[('mesh', 'links[0]', 'links[0] mesh 1-2'), ('mesh', 'links[1]', 'links[1] mesh 4-5'),
 ('bearing', 'links[6]', 'bearing 3-7'), ('bearing', 'links[7]', 'bearing 1-0')]
"""
from __future__ import annotations

from contextlib import contextmanager
from typing import Any, Callable, Iterable, Iterator

from powergraph.model.graph import unique_name
from powergraph.model.spec import Model
from powergraph.records import record


@record
class LossSource:
    """One loss source of a model (see the module docstring).

    ``between`` are the two members (component ids; the frame second for a drag against
    the housing), ``link`` the link it stands for (None for a component's drag or a
    machine); ``friction`` and ``drag`` its laws (None when absent; a mesh's
    ``friction`` is its load-dependent efficiency block); ``loaded_by`` the meshes whose
    tooth forces load its friction: ``(mesh link, gear, working pitch radius m, mesh
    instances)``; ``applied`` how the solve applies it (see the module docstring).
    """

    kind: str
    path: str
    node: str
    link: int | None
    between: tuple[str, str]
    instances: int
    friction: Any = None
    drag: Any = None
    loaded_by: tuple[tuple[int, str, float, int], ...] = ()
    applied: str = "torque"

    @property
    def label(self) -> str:
        """Its name among a duty cycle's losses: ``links[2] mesh S-P``, ``bearing 3-7``,
        ``machine MG1``."""
        return f"machine {self.node}" if self.applied == "machine" else self.node

    def loss(self, result: Any) -> float:
        """This source's loss in ``result`` (a power-flow result of its model), W."""
        if self.applied == "element":
            return sum(e.loss for e in result.elements if e.link == self.link)
        if self.applied == "machine":
            return sum(m.loss for m in result.machines if m.name == self.node)
        return sum(b.loss for b in result.bearings if b.node == self.node)


def meshes(model: Model) -> Iterator[LossSource]:
    """Each mesh, and each coupling with an efficiency below 1 (an element's factor)."""
    for link in model.links:
        if link.type == "mesh" or (link.type == "coupling" and link.efficiency < 1.0):
            yield LossSource(link.type, link.path, element_label(model, link.index),
                             link.index, link.between,
                             max(model.components[c].count for c in link.between),
                             friction=link.blocks.get("friction"), applied="element")


def element_label(model: Model, link: int) -> str:
    """``links[2] mesh S-P``: the label of a mesh's or coupling's loss.

    >>> from powergraph.model import load_model
    >>> element_label(load_model("models/rv40e.yaml"), 0)
    'links[0] mesh 1-2'
    """
    lk = model.links[link]
    a, b = (model.raw_id(c) for c in lk.between)
    return f"links[{link}] {lk.type} {a}-{b}"


#: The link types that carry torque loss blocks.
TORQUE_LINKS = ("bearing", "seal")


def bearings(model: Model) -> Iterator[LossSource]:
    """Each bearing link with a ``friction:`` or ``drag:`` block (an open clutch or brake
    with its drag included), and each seal (kind ``seal``)."""
    if not any(link.type in TORQUE_LINKS and link.blocks for link in model.links):
        return
    from powergraph.model.block_bearing import gear_radius, load_meshes  # trains with them

    names: set[str] = set()
    for link in model.links:
        if link.type not in TORQUE_LINKS or not link.blocks:
            continue
        carried, carrying = link.between
        friction = link.blocks.get("friction")
        loaded = tuple(
            (mesh, gear, gear_radius(model, mesh, gear),
             max(model.components[c].count for c in model.links[mesh].between))
            for mesh, gear in (load_meshes(model, carried) if friction is not None else ()))
        # unique among the bearings (ids may contain "-"; two bearings may join a pair)
        node = unique_name(f"{link.type} {model.raw_id(carried)}-{model.raw_id(carrying)}",
                           names)
        names.add(node)
        yield LossSource(link.type, link.path, node, link.index, (carried, carrying),
                         max(model.components[c].count for c in link.between), friction,
                         link.blocks.get("drag"), loaded)


def drags(model: Model) -> Iterator[LossSource]:
    """Each component with a ``drag:`` block, and each gear dipped in the sump
    (``churning:``), against the housing."""
    for component in model.components.values():
        for kind, law in (("drag", component.drag), ("churning", component.churning)):
            if law is not None:
                yield LossSource(kind, f"components.{component.raw_id}.{kind}",
                                 f"{kind} {component.raw_id}", None,
                                 (component.id, model.frame), component.count, None, law)


def machines(model: Model) -> Iterator[LossSource]:
    """Each electric machine (its loss set by the bus balance)."""
    if not model.machines:
        return
    from powergraph.statics.machines import machine_name  # trains with machines

    for port in model.machines:
        yield LossSource("machine", port.path, machine_name(port, model), None,
                         (port.component, model.frame), 1, applied="machine")


#: The registered builders, in the order their sources are listed.
BUILDERS: list[Callable[[Model], Iterable[LossSource]]] = [meshes, bearings, drags, machines]


def loss_sources(model: Model) -> tuple[LossSource, ...]:
    """Every loss source of ``model``, built once per model (and per set of builders)."""
    key = ("statics.loss_sources", tuple(BUILDERS))
    found = model.derived.get(key)
    if found is None:
        found = model.derived[key] = tuple(s for build in BUILDERS for s in build(model))
    return found


def torque_sources(model: Model) -> tuple[LossSource, ...]:
    """The sources applied as torques opposing a relative rotation (``applied ==
    "torque"``): what the bearing iteration solves for."""
    key = ("statics.torque_sources", tuple(BUILDERS))
    found = model.derived.get(key)
    if found is None:
        found = model.derived[key] = tuple(s for s in loss_sources(model)
                                           if s.applied == "torque")
    return found


def law_caveats(result: Any) -> tuple:
    """The warnings of the torque sources' laws at the result's speeds (a law with a
    ``caveat(relative speed, path)``: e.g. churning between its fits)."""
    states = {state.node: state for state in getattr(result, "bearings", ())}
    found = []
    for source in torque_sources(result.model):
        state = states.get(source.node)
        for law in (source.friction, source.drag):
            if state is not None and hasattr(law, "caveat"):
                found.append(law.caveat(state.relative_speed, source.path))
    return tuple(c for c in found if c is not None)


def losses(result: Any) -> tuple[tuple[LossSource, float], ...]:
    """Each loss source of ``result``'s model with its loss in ``result`` (W); together
    they are the result's total loss.

    >>> import powergraph as pg
    >>> result = pg.solve(pg.load_model("models/rv40e.yaml"))
    >>> abs(sum(w for _, w in losses(result)) - result.total_loss) < 1e-9 * result.total_loss
    True
    """
    return tuple((source, source.loss(result)) for source in loss_sources(result.model))


@contextmanager
def registered(builder: Callable[[Model], Iterable[LossSource]]) -> Iterator[None]:
    """Register ``builder`` for the duration of a ``with`` block (a loss type defined
    outside the package, e.g. in a test)."""
    BUILDERS.append(builder)
    try:
        yield
    finally:
        BUILDERS.remove(builder)
