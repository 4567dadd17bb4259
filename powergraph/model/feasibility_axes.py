"""Coaxiality of a planet's meshes, rings not marked internal, and the geometry a mesh
gives (module, shifts): part of :mod:`powergraph.model.feasibility` (docs/feasibility.md).

Examples
--------
>>> from powergraph.model.spec import Component, Link
>>> sun, planet = Component("s", "s", teeth=23), Component("p", "p", teeth=24, count=3)
>>> ring = Component("r", "r", teeth=72, internal=True)
>>> links = [Link(i, "mesh", pair, pair, carrier="c") for i, pair in
...          enumerate([("s", "p"), ("p", "r")])]
>>> found, centre, mm = coaxiality([(links[0], sun, planet), (links[1], ring, planet)])
>>> found[0].path, found[0].code, centre
('links[0..1]', 'coaxiality', None)
"""
from __future__ import annotations

from typing import Any, NamedTuple

from powergraph.errors import Caveat
from powergraph.gears import planetary

#: Working centre distances (mm) of one planet agree within this fraction.
CENTRE_TOLERANCE = 2e-4


class _Centre(NamedTuple):
    """One central mesh of a planet: its centre distance in half-modules (one module, no
    shift) and in mm when a module is known (working, with the mesh's shifts)."""

    link: Any
    central: Any
    planet: Any
    teeth: int
    mm: float | None

    def words(self) -> str:
        if self.central.internal:
            return f"ring {self.central.teeth} − planet {self.planet.teeth} = {self.teeth}"
        return f"sun {self.central.teeth} + planet {self.planet.teeth} = {self.teeth}"


def mesh_centre(link: Any, central: Any, planet: Any) -> _Centre:
    """The centre distance of a mesh (``central`` may be another planet, external)."""
    teeth = planetary.centre_distance(central.teeth, planet.teeth, central.internal)
    geometry = mesh_geometry(link)
    if geometry is not None:
        mm = planetary.working_centre_distance(
            geometry.teeth_1, geometry.teeth_2, geometry.internal, geometry.module,
            geometry.pressure_angle_deg, geometry.helix_angle_deg, geometry.shift_1,
            geometry.shift_2)
    else:
        module = gear_module(central) or gear_module(planet)
        mm = None if module is None else module * teeth / 2
    return _Centre(link, central, planet, teeth, mm)


def mesh_geometry(link: Any) -> Any:
    """The involute geometry of a mesh (its ``geometry`` block, alone or with friction)."""
    if "geometry" in link.blocks:
        return link.blocks["geometry"]
    return getattr(link.blocks.get("friction"), "geometry", None)


def gear_module(component: Any) -> float | None:
    return getattr(component.geometry, "module", None)


def coaxiality(meshes: list[tuple]) -> tuple[list[Caveat], float | None, float | None]:
    """Caveats on one planet's central meshes ``(link, central gear, planet gear)``, and its
    centre distance (half-modules, and mm when every mesh gives a module) when they agree."""
    centres = [mesh_centre(*m) for m in meshes]
    if not centres:
        return [], None, None
    rings = _rings_not_internal(centres)
    if rings:
        return rings, None, None
    if all(c.mm is not None for c in centres):
        spread = max(c.mm for c in centres) - min(c.mm for c in centres)
        if spread <= CENTRE_TOLERANCE * max(c.mm for c in centres):
            return [], float(centres[0].teeth), centres[0].mm
        text = ", ".join(f"{place([c.link])} {c.mm:.4g} mm" for c in centres)
        return [Caveat(f"the working centre distances of planet {_planet_name(centres)}'s "
                       f"meshes differ ({text}): the planets cannot share the axis of "
                       "the central gears", place([c.link for c in centres]),
                       "coaxiality")], None, None
    if len({c.teeth for c in centres}) == 1:
        return [], float(centres[0].teeth), None
    return [Caveat(_coaxiality_words(centres), place([c.link for c in centres]),
                   "coaxiality")], None, None


def _coaxiality_words(centres: list[_Centre]) -> str:
    simple = len(centres) == 2 and centres[0].planet.id == centres[1].planet.id and \
        sorted(c.central.internal for c in centres) == [False, True]
    if simple:
        sun, ring = sorted(centres, key=lambda c: c.central.internal)
        zs, zp, zr = sun.central.teeth, sun.planet.teeth, ring.central.teeth
        return (f"sun {zs} + 2 × planet {zp} = {zs + 2 * zp} ≠ ring {zr}: the planets "
                "cannot share the axis of sun and ring (one module, no profile shift; give "
                "the meshes' geometry with their shifts if they are shifted)")
    text = "; ".join(c.words() for c in centres)
    return (f"the centre distances of planet {_planet_name(centres)}'s meshes differ, in "
            f"half-modules: {text}: the planets cannot share the axis of the central gears "
            "(one module, no profile shift; give the meshes' geometry with their shifts if "
            "they are shifted)")


def _planet_name(centres: list[_Centre]) -> str:
    """The planet's gears (its steps) meshing the central gears: ``p1/p2``."""
    return "/".join(sorted({c.planet.id for c in centres}))


def _rings_not_internal(centres: list[_Centre]) -> list[Caveat]:
    """An external central gear that fits as a ring (its teeth minus the planet's give the
    other meshes' centre distance ``D``) or surrounds the planets (its pitch radius, ``z``
    half-modules, reaches beyond theirs, ``D + z_p``): it should be ``internal: true``."""
    out = []
    for c in centres:
        others = {o.teeth for o in centres if o is not c}
        if c.central.internal or len(others) != 1:
            continue
        (other,) = others
        z, zp = c.central.teeth, c.planet.teeth
        if other == c.teeth or z - zp < other:
            continue
        fits = (f"as a ring it would mesh at {z} − {zp} = {z - zp}" if z - zp == other else
                f"its pitch circle (radius {z}) surrounds the planets' ({other} + {zp} = "
                f"{other + zp})")
        out.append(Caveat(
            f"gear {c.central.id} ({z} teeth) meshes planet {c.planet.id} ({zp}) like a "
            f"ring: the planet's other mesh puts its axis at {other} half-modules and {fits}, "
            "but it is not internal, so the mesh's ratio has the wrong sign; write "
            "internal: true", f"components.{c.central.raw_id}", "ring-not-internal"))
    return out


def place(links: list) -> str:
    """``links[3]``, ``links[0..1]`` (consecutive) or ``links[0,3]``."""
    index = sorted({link.index for link in links})
    if len(index) == 1:
        return f"links[{index[0]}]"
    if index == list(range(index[0], index[-1] + 1)) and len(index) == 2:
        return f"links[{index[0]}..{index[1]}]"
    return f"links[{','.join(map(str, index))}]"
