"""A train in one of its modes (docs/modes.md): the model with the mode's clutches and
brakes engaged (rigid, exactly as a ``fixed`` link) and every other shift element open
(no constraint, only its drag in its slip speed).

Freewheels are engaged or overrunning as ``freewheels`` says (default: overrunning); which
state is consistent is decided by :func:`powergraph.statics.modes.solve_mode`. Freewheels
that join the same two bodies of the mode are one element in parallel
(:func:`freewheel_groups`), decided once. Problems name the mode: ``modes.R: ...``.

Examples
--------
>>> from powergraph.model import load_model
>>> model = load_model("models/simpson_3speed.yaml")            # doctest: +SKIP
>>> first = resolve(model, "1")                                 # doctest: +SKIP
>>> first.mode, [b.id for b in first.bodies][:2]                # doctest: +SKIP
('1', ['0/c2', 'in/r1'])
"""
from __future__ import annotations

import dataclasses
from types import MappingProxyType
from typing import Iterable, Mapping

from powergraph.errors import ModelError
from powergraph.model.spec_parts import ShiftElement
from powergraph.records import record

# ``Model`` is named as text, not imported: ``Model.in_mode`` (powergraph.model.spec) calls
# :func:`resolve` here.


def mode_path(mode: str) -> str:
    """The place of a mode in the file, for messages (``modes.R``)."""
    return f"modes.{mode}"


def engaged_in(model: Model, mode: str) -> tuple[str, ...]:
    """The clutches and brakes the mode engages (UsageError-free: ModelError when unknown)."""
    if mode not in model.modes:
        known = ", ".join(model.modes) or "none"
        raise ModelError(f"unknown mode {mode!r} (the model's modes: {known})", "modes")
    return model.modes[mode]


def resolve(model: Model, mode: str | None,
            freewheels: Mapping[str, bool] | None = None,
            engaged: Iterable[str] | None = None) -> Model:
    """The model in ``mode`` (a key of ``model.modes``), or with the elements ``engaged``.

    Parameters
    ----------
    model : Model
        A model with shift elements (any model: one without is returned unchanged).
    mode : str or None
        The mode; None with ``engaged`` to engage a set of elements by name.
    freewheels : mapping, optional
        ``{freewheel name: engaged?}``; freewheels not named overrun.
    engaged : iterable of str, optional
        The engaged clutch/brake names when ``mode`` is None.

    Returns
    -------
    Model
        A new model at the mode's operating point
        (:func:`powergraph.model.mode_specs.at_mode_point`: its inactive ports carrying
        nothing, the ports and buses it gives), whose ``links`` hold each shift element as
        ``fixed`` (engaged) or ``bearing`` (open), with its bodies rebuilt, ``mode`` set
        and the mode in its name (``Simpson 3-speed [R]``). Components joined to no active
        port and not to the frame are ``idle`` (:func:`idle_components`): held in the
        frame's body, their links carrying nothing.

    Raises
    ------
    ModelError
        ``modes.NAME: engages ...: ...`` when the mode joins what cannot be joined (a
        port held by a brake, a mesh inside one rigid body...).
    """
    from powergraph.model.graph import bodies_of, check_topology
    from powergraph.model.mode_specs import at_mode_point
    from powergraph.model.shift import as_link

    names = set(engaged_in(model, mode) if mode is not None else (engaged or ()))
    model = at_mode_point(model, mode)
    names |= {n for n, on in (freewheels or {}).items() if on}
    links = list(model.links)
    for element in model.shift_elements:
        links[element.index] = as_link(element, element.name in names)
    bodies, body_of = bodies_of(model.components, tuple(links))
    idle = idle_components(model, links, bodies, body_of)
    components = model.components
    if idle:
        links, components, bodies, body_of = _held_idle(model, links, bodies, body_of, idle)
    derived = dataclasses.replace(model, links=tuple(links), bodies=bodies,
                                  body_of=body_of, mode=mode, resolved=True,
                                  components=components, idle=frozenset(idle),
                                  name=model.name if mode is None else f"{model.name} [{mode}]")
    try:
        check_topology(derived)
    except ModelError as error:
        where = mode_path(mode) if mode is not None else error.path
        raise ModelError(f"engages {_listing(names)}: {error.message}", where) from None
    return derived


def default_state(model: Model) -> Model:
    """A loaded model with modes as its solve takes it: the first mode (its operating
    point, its idle members held) with the freewheels as loaded, still marked not
    resolved, so that its solve warns ``default-state`` (docs/modes.md).

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> m = default_state(load_model("models/honda_immd.yaml"))
    >>> m.mode, sorted(m.inactive), m.resolved
    ('engine drive', [1], False)
    """
    holding = {e.name: model.links[e.index].type == "fixed" for e in model.shift_elements
               if e.kind == "freewheel"}
    resolved = resolve(model, next(iter(model.modes)), holding)
    return dataclasses.replace(resolved, resolved=False, name=model.name,
                               point_of=resolved.point_of or resolved.mode)


def idle_components(model: Model, links, bodies, body_of: Mapping[str, str]) -> set[str]:
    """The components joined to no active port and not to the frame (docs/modes.md):
    the bodies of ``links`` (meshes joining their two gears and carrier — a pair the frame
    carries only its two gears: on fixed axes it can turn by itself —, couplings and
    freewheels — held or not — their two members) grouped, and every group without the
    frame's body or an active port's body.

    Examples
    --------
    >>> from powergraph.model import model_from_dict
    >>> m = model_from_dict({"name": "x", "components": {0: {"role": "frame"},
    ...     1: {"teeth": 20}, 2: {"teeth": 40}, "e": {}},
    ...     "links": [{"type": "mesh", "between": [1, 2]},
    ...               {"type": "clutch", "name": "C", "between": ["e", 1]}],
    ...     "ports": [{"component": "e", "role": "input"}, {"component": 1, "role": "input"},
    ...               {"component": 2, "role": "output"}]})
    >>> sorted(idle_components(m, m.links, m.bodies, m.body_of))
    []
    >>> sorted(idle_components(dataclasses.replace(m, inactive=frozenset({0})), m.links,
    ...                        m.bodies, m.body_of))
    ['e']
    """
    root = {b.id: b.id for b in bodies}

    def find(x: str) -> str:
        while root[x] != x:
            root[x] = root[root[x]]
            x = root[x]
        return x

    def join(*members: str) -> None:
        first = find(body_of[members[0]])
        for other in members[1:]:
            root[find(body_of[other])] = first

    kinds = {e.index: e.kind for e in model.shift_elements}
    for link in links:
        if link.type == "mesh" and body_of[link.carrier] == body_of[model.frame]:
            join(*link.between)       # a gear pair on fixed axes: it may turn on its own
        elif link.type == "mesh":
            join(link.between[0], link.between[1], link.carrier)
        elif link.type == "coupling" or kinds.get(link.index) == "freewheel":
            join(*link.between)
    live = {find(body_of[model.frame])} | {find(body_of[p.component]) for p in model.ports
                                           if p.index not in model.inactive}
    return {c for c in model.components if find(body_of[c]) not in live}


def _held_idle(model: Model, links: list, bodies, body_of, idle: set[str]):
    """The idle components held in the frame's body (it keeps its name), their links
    carrying nothing (a ``bearing`` without losses at the same place: a mesh or coupling
    among them, a bearing's or an open element's drag, a seal) and their own drag and
    churning left out: nothing loads them, so they turn at no speed the train sets."""
    from powergraph.model.spec_parts import Body, Link

    for i, link in enumerate(links):
        if link.type != "fixed" and idle & {*link.between, link.carrier}:
            links[i] = Link(index=link.index, type="bearing", between=link.between,
                            raw_between=link.raw_between, name=link.name)
    components = MappingProxyType({
        c: dataclasses.replace(comp, drag=None, churning=None) if c in idle else comp
        for c, comp in model.components.items()})
    frame = next(b for b in bodies if b.is_frame)
    members = tuple(c for c in model.components if body_of[c] == frame.id or c in idle)
    held = Body(id=frame.id, members=members, is_frame=True)
    bodies = tuple(held if b.is_frame else b for b in bodies
                   if b.is_frame or not idle & set(b.members))
    body_of = MappingProxyType({c: frame.id if c in idle else b for c, b in body_of.items()})
    return links, components, bodies, body_of


def _listing(names: Iterable[str]) -> str:
    names = sorted(names)
    return ", ".join(names) if names else "nothing"


@record
class FreewheelGroup:
    """The freewheels of a mode that join the same two bodies: one element in parallel.

    ``bodies`` ``(X, Y)`` are the bodies of the first member's ``between[0]`` and
    ``between[1]``; ``orients[i]`` is +1 when member ``i`` is written ``[X side, Y side]``,
    -1 when written reversed; ``senses[i]`` is +1 when member ``i`` allows
    ``w_X - w_Y >= 0`` (holds a torque ``>= 0`` on the X side), -1 when it allows ``<= 0``.
    """

    members: tuple[ShiftElement, ...]
    bodies: tuple[str, str]
    orients: tuple[int, ...]
    senses: tuple[int, ...]

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(m.name for m in self.members)

    @property
    def links(self) -> tuple[int, ...]:
        return tuple(m.index for m in self.members)

    @property
    def label(self) -> str:
        """``F1``, ``F1+F2``, or ``F1+F2+…+F9 (9 in parallel)``."""
        names = self.names
        if len(names) <= 3:
            return "+".join(names)
        return f"{names[0]}+{names[1]}+…+{names[-1]} ({len(names)} in parallel)"


def freewheel_groups(base: Model) -> tuple[FreewheelGroup, ...]:
    """The freewheels ``base`` leaves to decide, grouped by the two bodies they join.

    Parameters
    ----------
    base : Model
        A model in a mode with its freewheels open (:func:`resolve` without
        ``freewheels``).

    Returns
    -------
    tuple of FreewheelGroup
        In file order of their first members. A freewheel whose two members the mode
        already joins (``idle``) is in none.

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> base = resolve(load_model("models/simpson_3speed.yaml"), "1")     # doctest: +SKIP
    >>> [(g.names, g.bodies, g.senses) for g in freewheel_groups(base)]   # doctest: +SKIP
    [(('F1',), ('c2', '0'), (1,))]
    """
    found: dict[frozenset, list[ShiftElement]] = {}
    for element in base.shift_elements:
        x, y = (base.body_of[c] for c in element.between)
        if element.kind == "freewheel" and x != y:
            found.setdefault(frozenset((x, y)), []).append(element)
    groups = []
    for members in found.values():
        x = base.body_of[members[0].between[0]]
        orients = tuple(1 if base.body_of[m.between[0]] == x else -1 for m in members)
        senses = tuple(o * (1 if m.holds == "positive" else -1)
                       for o, m in zip(orients, members))
        bodies = (x, base.body_of[members[0].between[1]])
        groups.append(FreewheelGroup(tuple(members), bodies, orients, senses))
    return tuple(groups)
