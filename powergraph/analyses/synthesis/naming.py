"""Readable names for a synthesised train: roles of its links and gears, what tells two
layouts of one graph apart, and the text of its tooth numbers.

A layout (:mod:`~powergraph.analyses.synthesis.teeth`) knows which coaxial gear is a sun
and which a ring, and which links are planets; these names come from it, so a designer
reads ``sun L1=12, planet L2=45, ring L0=102`` rather than gear ids (``g0a``).

Examples
--------
>>> from powergraph.analyses.synthesis.synthesize_classics import CLASSICS
>>> from powergraph.analyses.synthesis.teeth import layouts
>>> simple = next(iter(layouts(CLASSICS["2K-H"])))
>>> sorted(gear_names(simple).items())
[('g0a', 'ring L1'), ('g0b', 'planet L2'), ('g1a', 'planet L2'), ('g1b', 'sun L0')]
>>> teeth_text({"g0a": 72, "g0b": 24, "g1a": 24, "g1b": 24}, gear_names(simple))
'sun L0=24, planet L2=24, ring L1=72'
"""
from __future__ import annotations

from collections import Counter
from typing import Mapping

from powergraph.analyses.synthesis.teeth import Layout

#: Order of the roles in a tooth list: the way a designer reads a planetary train.
ROLE_ORDER = ("sun", "planet", "ring")


def role_names(layout: Layout) -> dict[int, str]:
    """A readable role per coaxial link: ``carrier``, ``sun``, ``ring``, ``crank``,
    ``output disk`` (coupled), joined by ``+`` for a link with several."""
    st, graph = layout.structure, layout.graph
    internal = layout.internal
    roles: dict[int, list[str]] = {c: [] for c in st.coaxial}
    for k, (u, v, carrier) in enumerate(graph.gear_pairs):
        if carrier in roles:
            name = "crank" if st.kinds[k] == "khv" else "carrier"
            if name not in roles[carrier]:
                roles[carrier].append(name)
        side = st.coaxial_side[k]
        if side is not None:
            link = (u, v)[side]
            name = "ring" if internal.get(k) == side else "sun"
            if name not in roles[link]:
                roles[link].append(name)
    for u, v in graph.couplings:
        for link in (u, v):
            if link in roles:
                roles[link].append("output disk")
    return {c: "+".join(r) or "link" for c, r in roles.items()}


def link_names(layout: Layout, fixed: int) -> dict[int, str]:
    """A name per link: its role and number (``sun L1``, ``planet L2``, ``cycloid L4``),
    the fixed link marked ``(fixed)``."""
    roles = role_names(layout)
    coupled = layout.structure.coupled
    names = {}
    for link in range(layout.graph.links):
        role = roles.get(link) or ("cycloid" if link in coupled else "planet")
        names[link] = f"{role} L{link}" + (" (fixed)" if link == fixed else "")
    return names


def pin_note(layout: Layout) -> str:
    """What tells this graph from another of the same links and gears: the planets that
    turn on one pin (``L2+L3 on one pin``); empty when each planet has its own.

    Two displacement graphs can differ only in that, and then give the same model file
    and figures: the note is what distinguishes their rows."""
    from powergraph.analyses.synthesis.enumerate import axes_of

    coaxial = set(layout.structure.coaxial)
    notes = []
    for axis in axes_of(layout.graph):
        planets = sorted(axis - coaxial)
        if axis & coaxial and len(planets) >= 2:
            notes.append("+".join(f"L{p}" for p in planets) + " on one pin")
    return ", ".join(notes)


def gear_names(layout: Layout) -> dict[str, str]:
    """``{gear id: name}``: each gear's role on its link (``sun``, ``ring``, ``planet``,
    ``cycloid``) and the link's number; the two gears of a simple planet share a name."""
    st, internal = layout.structure, layout.internal
    names = {}
    for k, (u, v, _) in enumerate(layout.graph.gear_pairs):
        for side, link in enumerate((u, v)):
            if st.coaxial_side[k] == side:
                role = "ring" if internal.get(k) == side else "sun"
            else:
                role = "cycloid" if link in st.coupled else "planet"
            names[f"g{k}{'ab'[side]}"] = f"{role} L{link}"
    return names


def member_names(layout: Layout) -> dict[str, str]:
    """``{"L1": "sun 1", ...}``: each link by its role and planetary **set** (a carrier
    with its planets, numbered in link order; no number when there is one set):
    ``sun 2``, ``ring 1+carrier 2``, ``planet 1`` (``planet 1a``, ``1b`` when a set has
    several planet links), ``cycloid``, ``crank``, ``output disk``.

    >>> from powergraph.analyses.synthesis.synthesize_classics import CLASSICS
    >>> from powergraph.analyses.synthesis.teeth import layouts
    >>> sorted(member_names(layouts(CLASSICS["2K-H"])[0]).items())
    [('L0', 'sun'), ('L1', 'ring'), ('L2', 'planet'), ('L3', 'carrier')]
    """
    st, graph, internal = layout.structure, layout.graph, layout.internal
    carriers = sorted({c for *_, c in graph.gear_pairs if c in st.coaxial})
    number = {c: "" if len(carriers) == 1 else f" {j}" for j, c in enumerate(carriers, 1)}
    roles: dict[int, list[str]] = {}

    def add(link: int, role: str) -> None:
        if role not in roles.setdefault(link, []):
            roles[link].append(role)

    planets: dict[int, list[int]] = {}
    for k, (u, v, carrier) in enumerate(graph.gear_pairs):
        tag = number.get(carrier, "")
        if carrier in st.coaxial:
            add(carrier, ("crank" if st.kinds[k] == "khv" else "carrier") + tag)
        for side, link in enumerate((u, v)):
            if st.coaxial_side[k] == side:
                add(link, ("ring" if internal.get(k) == side else "sun") + tag)
            elif link in st.coupled:
                add(link, "cycloid")
            elif link not in planets.setdefault(carrier, []):
                planets[carrier].append(link)
    for carrier, links in planets.items():
        for link in links:
            add(link, f"planet{number.get(carrier, '')}")
    for u, v in graph.couplings:
        for link in (u, v):
            if link in st.coaxial:
                add(link, "output disk")
    names = {n: "+".join(r) for n, r in sorted(roles.items())}
    count = Counter(names.values())
    seen: Counter = Counter()
    for n, name in names.items():        # two suns of one set: sun a, sun b
        if count[name] > 1:
            names[n] = f"{name} {'abcdefghij'[seen[name]]}"
            seen[name] += 1
    return {f"L{n}": name for n, name in names.items()}


def teeth_text(teeth: Mapping[str, int], names: Mapping[str, str]) -> str:
    """The tooth numbers by gear name, suns first, then planets, then rings; the gears of
    one link with one name (a simple planet) listed once, a stepped planet as ``45/51``.

    >>> teeth_text({"g0a": 12, "g0b": 45, "g1a": 51}, {"g0a": "sun L1", "g0b": "planet L2",
    ...                                                "g1a": "planet L2"})
    'sun L1=12, planet L2=45/51'
    """
    grouped: dict[str, list[int]] = {}
    for gear, z in teeth.items():
        values = grouped.setdefault(names.get(gear, gear), [])
        if z not in values:
            values.append(z)

    def order(name: str) -> tuple:
        role = name.split(" ")[0]
        return (ROLE_ORDER.index(role) if role in ROLE_ORDER else len(ROLE_ORDER), name)

    return ", ".join(f"{name}=" + "/".join(map(str, grouped[name]))
                     for name in sorted(grouped, key=order))


def arrangement_name(layout: Layout, fixed: int, input_: int, output: int) -> str:
    """E.g. ``2K-H simple: sun L1 in, carrier L3 out, ring L0 fixed``, with the
    :func:`pin_note` when planets share a pin."""
    roles = role_names(layout)
    graph = layout.graph.name or f"{layout.graph.links}-link"
    note = pin_note(layout)
    return (f"{graph} {layout.name}: {roles[input_]} L{input_} in, {roles[output]} L{output} "
            f"out, {roles[fixed]} L{fixed} fixed" + (f"; {note}" if note else ""))
