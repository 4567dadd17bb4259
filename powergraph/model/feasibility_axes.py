"""Coaxiality of a planet's meshes, rings not marked internal, rings meshing without a
carrier, and the geometry a mesh gives (module, shifts): part of
:mod:`powergraph.model.feasibility` (docs/feasibility.md).

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


class _Centre(NamedTuple):
    """One central mesh of a planet: its centre distance in half-modules (one module, no
    shift) and in mm when a module is known (working, with the mesh's shifts, or its
    stated operating ``centre_distance``), with that module and where the mm come from."""

    link: Any
    central: Any
    planet: Any
    teeth: int
    mm: float | None
    module: float | None = None
    source: str = ""

    def words(self) -> str:
        if self.central.internal:
            return f"ring {self.central.teeth} − planet {self.planet.teeth} = {self.teeth}"
        return f"sun {self.central.teeth} + planet {self.planet.teeth} = {self.teeth}"


def mesh_centre(link: Any, central: Any, planet: Any, modules: dict | None = None
                ) -> _Centre:
    """The centre distance of a mesh (``central`` may be another planet, external). A mesh
    without a geometry block is unshifted, with its gears' module: a gear's own
    ``geometry`` gives it, else ``modules`` (gear id -> module, from other meshes' blocks:
    :func:`geometry_modules`)."""
    teeth = planetary.centre_distance(central.teeth, planet.teeth, central.internal)
    geometry = mesh_geometry(link)
    if geometry is None:
        modules = modules or {}
        module = (gear_module(central) or gear_module(planet) or modules.get(central.id)
                  or modules.get(planet.id))
        if module is None:
            return _Centre(link, central, planet, teeth, None)
        return _Centre(link, central, planet, teeth, module * teeth / 2, module,
                       f"unshifted, module {module:g}")
    stated = getattr(geometry, "centre_distance", None)
    if stated is not None:
        return _Centre(link, central, planet, teeth, stated, geometry.module,
                       "its centre_distance")
    mm = planetary.working_centre_distance(
        geometry.teeth_1, geometry.teeth_2, geometry.internal, geometry.module,
        geometry.pressure_angle_deg, geometry.helix_angle_deg, geometry.shift_1,
        geometry.shift_2)
    return _Centre(link, central, planet, teeth, mm, geometry.module,
                   f"shifts {geometry.shift_1:g}, {geometry.shift_2:g}")


def mesh_geometry(link: Any) -> Any:
    """The involute geometry of a mesh (its ``geometry`` block, alone or with friction): a
    :class:`~powergraph.gears.mesh_loss.MeshGeometry`, or an
    :class:`~powergraph.model.block_friction.OperatingGeometry` (a ``centre_distance``
    without shifts)."""
    if "geometry" in link.blocks:
        return link.blocks["geometry"]
    return getattr(link.blocks.get("friction"), "geometry", None)


def stated_only(geometry: Any) -> bool:
    """The geometry gives an operating ``centre_distance`` and no shifts (an
    :class:`~powergraph.model.block_friction.OperatingGeometry`: a shift sum, no split)."""
    return hasattr(geometry, "shift_sum")


def gear_module(component: Any) -> float | None:
    return getattr(component.geometry, "module", None)


def geometry_modules(model: Any) -> dict[str, float]:
    """Gear id -> the module of the first mesh geometry block naming the gear."""
    modules: dict[str, float] = {}
    for link in model.meshes:
        geometry = mesh_geometry(link)
        if geometry is not None:
            for gear in link.between:
                modules.setdefault(gear, geometry.module)
    return modules


def coaxiality(meshes: list[tuple], modules: dict | None = None
               ) -> tuple[list[Caveat], float | None, float | None]:
    """Caveats on one planet's central meshes ``(link, central gear, planet gear)``, and its
    centre distance (half-modules, and mm when every mesh gives a module) when they agree:
    in mm within :func:`planetary.centre_tolerance` of the smallest module. ``modules``:
    as :func:`mesh_centre`."""
    centres = [mesh_centre(*m, modules) for m in meshes]
    if not centres:
        return [], None, None
    rings = _rings_not_internal(centres)
    if rings:
        return rings, None, None
    if all(c.mm is not None for c in centres):
        spread = max(c.mm for c in centres) - min(c.mm for c in centres)
        module = min(c.module for c in centres)
        tolerance = planetary.centre_tolerance(module)
        if spread <= tolerance:
            return [], float(centres[0].teeth), centres[0].mm
        text = "; ".join(f"{place([c.link])} {c.mm:.4f} mm ({c.source})" for c in centres)
        return [Caveat(f"the working centre distances of planet {_planet_name(centres)}'s "
                       f"meshes differ: {text}; {spread * 1e3:.1f} µm apart, more than "
                       f"{planetary.CENTRE_TOLERANCE:g} module = {tolerance * 1e3:.3g} µm: "
                       "the planets cannot share the axis of the central gears",
                       place([c.link for c in centres]), "coaxiality")], None, None
    if len({c.teeth for c in centres}) == 1:
        return [], float(centres[0].teeth), None
    return [Caveat(_coaxiality_words(centres), place([c.link for c in centres]),
                   "coaxiality")], None, None


_UNSHIFTED = ("(one module, no profile shift; if the set is profile-shifted, give each of "
              "these meshes a geometry with its shifts or its centre_distance)")


def _coaxiality_words(centres: list[_Centre]) -> str:
    simple = len(centres) == 2 and centres[0].planet.id == centres[1].planet.id and \
        sorted(c.central.internal for c in centres) == [False, True]
    if simple:
        sun, ring = sorted(centres, key=lambda c: c.central.internal)
        zs, zp, zr = sun.central.teeth, sun.planet.teeth, ring.central.teeth
        return (f"sun {zs} + 2 × planet {zp} = {zs + 2 * zp} ≠ ring {zr}: the planets "
                f"cannot share the axis of sun and ring {_UNSHIFTED}")
    text = "; ".join(c.words() for c in centres)
    return (f"the centre distances of planet {_planet_name(centres)}'s meshes differ, in "
            f"half-modules: {text}: the planets cannot share the axis of the central gears "
            f"{_UNSHIFTED}")


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


def rings_without_carrier(model: Any, told: set[str]) -> list[Caveat]:
    """Meshes of an internal gear without ``carrier`` (or with the frame as carrier),
    read as fixed-axis pairs, whose external gear looks like a planet: it is carried by a
    ``bearing`` on a body other than the frame (``between: [planet, carrier]``, carried
    member first: that body is the carrier to write) or has ``count`` > 1. Not warned: an
    external gear borne by the housing (a bearing to the frame's body: its axis is fixed,
    as in a star set), a single gear with neither sign (a plain internal pair on fixed
    axes), and the links in ``told`` (paths already warned, e.g. ``planet-carrier``).

    Examples
    --------
    >>> from powergraph.model import model_from_dict
    >>> m = model_from_dict({"name": "p", "components": {0: {"role": "frame"},
    ...     "p": {"teeth": 20}, "r": {"teeth": 60, "internal": True}, "c": {}},
    ...     "links": [{"type": "mesh", "between": ["p", "r"]},
    ...               {"type": "bearing", "between": ["p", "c"]}],
    ...     "ports": [{"component": "c", "role": "input"},
    ...               {"component": "r", "role": "output"}]})
    >>> [(c.path, c.code, c.message[-16:]) for c in rings_without_carrier(m, set())]
    [('links[0]', 'ring-without-carrier', 'write carrier: c')]
    """
    frame, shifts = model.frame_body, {e.index for e in model.shift_elements}
    housed, carriers, on_frame = set(), {}, {}
    for link in model.links:
        if link.type != "bearing" or link.index in shifts:
            continue
        carried, carrying = (model.body_of[x] for x in link.between)
        if frame in (carried, carrying):
            housed.add(carrying if carried == frame else carried)
        elif carried != carrying:
            carriers.setdefault(carried, {}).setdefault(carrying, (link.between[1], link))
    for link in model.meshes:
        if link.carrier == model.frame:
            for body in {model.body_of[x] for x in link.between}:
                on_frame.setdefault(body, []).append(link.path)
    out = []
    for link in model.meshes:
        gears = [model.components[x] for x in link.between]
        if link.carrier != model.frame or link.path in told or \
                not any(g.internal for g in gears):
            continue
        ring, pinion = sorted(gears, key=lambda g: not g.internal)
        body = model.body_of[pinion.id]
        if body == frame or body in housed:
            continue
        found = [c for b, c in carriers.get(body, {}).items() if b != model.body_of[ring.id]]
        if found or max(model.components[x].count for x in model.body(body).members) > 1:
            others = [path for path in on_frame[body] if path != link.path]
            out.append(Caveat(_ring_words(model, ring, pinion, found, others), link.path,
                              "ring-without-carrier"))
    return out


def _ring_words(model: Any, ring: Any, pinion: Any, carriers: list, others: list) -> str:
    """The warning: the carrier to write (``carriers``: ``(component, bearing link)``),
    with the pinion's ``other`` meshes without carrier, or how to say the axis is fixed."""
    p, r = pinion.raw_id, ring.raw_id
    text = (f"mesh {p}-{r} has no carrier, so it is a fixed-axis pair (both axes held by "
            f"the housing), but {r} is internal: a ring nearly always meshes planets, whose "
            "axes turn with their carrier")
    if not carriers:
        frame = model.components[model.frame].raw_id
        return (f"{text}; write carrier: <the planets' carrier>, or, if {p} turns on a "
                f"fixed axis, give it a bearing on the housing (type: bearing, between: "
                f"[{p}, {frame}])")
    (carrier, bearing), *more = carriers
    also = f" (or {', '.join(str(model.raw_id(c)) for c, _ in more)})" if more else ""
    where = f", here and on {', '.join(others)}" if others else ""
    return (f"{text}; {p} is borne by {model.raw_id(carrier)} ({bearing.path}): write "
            f"carrier: {model.raw_id(carrier)}{also}{where}")
