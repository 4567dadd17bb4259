"""Loss sources: every torque loss the train's case carries besides its meshes.

A loss source applies a torque ``M >= 0`` to two bodies, opposing their relative rotation
``Δω``, and loses ``M·|Δω|``: a bearing's friction and drag, a component's drag against
the housing, an open clutch's drag (an open shift element is a bearing carrying its drag).
Each is described once, per model, by a :class:`LossSource`: its kind, its YAML path, its
label, the two members, its instances, its laws, and the meshes whose tooth forces load
it. Every evaluator takes the same list (:func:`loss_sources`): the single solve's
bearing iteration (:func:`powergraph.statics.bearings.bearing_states`), the batched
efficiency grid, the report's loss breakdown and the duty cycle's energy per element (both
from the states the solve returns), and the methods that read plain efficiencies and so
refuse such losses (:func:`places`).

A new loss type is one module with a builder — ``builder(model) -> iterable of
LossSource`` — and one line registering it (:data:`BUILDERS`, or :func:`registered` for a
builder that lives outside the package, e.g. in a test). Its laws are objects with a
vectorised ``torque(x)`` (N·m per instance, floats or arrays): ``friction.torque(radial
load)`` and ``drag.torque(relative speed)``, as the bearing blocks' laws.

Examples
--------
>>> from powergraph.model import load_model
>>> [(s.kind, s.path, s.node) for s in loss_sources(load_model("models/rv40e.yaml"))][:2]
[('bearing', 'links[6]', 'bearing 3-7'), ('bearing', 'links[7]', 'bearing 1-0')]
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
    the housing), ``link`` the link it stands for (None for a component's drag);
    ``friction`` and ``drag`` its laws (None when absent); ``loaded_by`` the meshes whose
    tooth forces load its friction: ``(mesh link, gear, working pitch radius m, mesh
    instances)``.
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


def bearings(model: Model) -> Iterator[LossSource]:
    """Each bearing link with a ``friction:`` or ``drag:`` block (an open clutch or brake
    with its drag included)."""
    if not any(link.type == "bearing" and link.blocks for link in model.links):
        return
    from powergraph.model.block_bearing import gear_radius, load_meshes  # trains with them

    names: set[str] = set()
    for link in model.links:
        if link.type != "bearing" or not link.blocks:
            continue
        carried, carrying = link.between
        friction = link.blocks.get("friction")
        loaded = tuple(
            (mesh, gear, gear_radius(model, mesh, gear),
             max(model.components[c].count for c in model.links[mesh].between))
            for mesh, gear in (load_meshes(model, carried) if friction is not None else ()))
        # unique among the bearings (ids may contain "-"; two bearings may join a pair)
        node = unique_name(f"bearing {model.raw_id(carried)}-{model.raw_id(carrying)}", names)
        names.add(node)
        yield LossSource("bearing", link.path, node, link.index, (carried, carrying),
                         max(model.components[c].count for c in link.between), friction,
                         link.blocks.get("drag"), loaded)


def drags(model: Model) -> Iterator[LossSource]:
    """Each component with a ``drag:`` block, against the housing."""
    for component in model.components.values():
        if component.drag is not None:
            yield LossSource("drag", f"components.{component.raw_id}.drag",
                             f"drag {component.raw_id}", None, (component.id, model.frame),
                             component.count, None, component.drag)


#: The registered builders, in the order their sources are listed.
BUILDERS: list[Callable[[Model], Iterable[LossSource]]] = [bearings, drags]


def loss_sources(model: Model) -> tuple[LossSource, ...]:
    """Every loss source of ``model``, built once per model (and per set of builders)."""
    key = ("statics.loss_sources", tuple(BUILDERS))
    found = model.derived.get(key)
    if found is None:
        found = model.derived[key] = tuple(s for build in BUILDERS for s in build(model))
    return found


def places(model: Model) -> list[str]:
    """The YAML paths of ``model``'s loss sources (``links[3]``, ``components.x.drag``)."""
    return [source.path for source in loss_sources(model)]


@contextmanager
def registered(builder: Callable[[Model], Iterable[LossSource]]) -> Iterator[None]:
    """Register ``builder`` for the duration of a ``with`` block (a loss type defined
    outside the package, e.g. in a test)."""
    BUILDERS.append(builder)
    try:
        yield
    finally:
        BUILDERS.remove(builder)
