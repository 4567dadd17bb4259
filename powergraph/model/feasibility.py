"""Can the train be built? The geometric feasibility of its planetary sets, as caveats.

A model can be valid and solvable and still describe gears that cannot be put together:
planets that cannot share the axis of their sun and ring, that cannot be assembled at equal
spacing, that collide with their neighbours; a ring gear not marked ``internal`` (its
ratio then has the wrong sign); a planet meshing with and without its carrier; a ring
meshing a planet without a carrier (read as a fixed-axis pair); an undercut pinion; a
gear given two tooth profiles by its meshes' geometry blocks (a planet's shift in its sun
pair must be its shift in its ring pair).
:func:`feasibility_caveats` finds them; validation adds them to
``Model.warnings`` (the answer of a solve stands, the designer should know), ``powergraph
check`` prints them and ``--strict`` refuses them. The conditions themselves are those of
:mod:`powergraph.gears.planetary` (one copy, shared with the tooth-number synthesis).

How a planetary set is read from the graph (docs/feasibility.md): the meshes on one
carrier (one rigid body) form a set; a **planet** is a gear with ``count`` > 1 or the
external partner of an internal gear, with its rigid body (the steps of a stepped
planet); the other gears of the set are **central** (suns and rings, coaxial with the
carrier). A planet joined to an output by a ``coupling`` (a K-H-V or cycloid stage), a
carrier with ``count`` > 1 (a crank) and meshes given by ``ratio`` (bevel gears) are not
2K-H planets and are left alone.

Examples
--------
>>> from powergraph.model import model_from_dict
>>> doc = {"name": "2K-H", "components": {0: {"role": "frame"}, "s": {"teeth": 23},
...        "p": {"teeth": 24, "count": 3}, "r": {"teeth": 72, "internal": True}, "c": {}},
...        "links": [{"type": "mesh", "between": ["s", "p"], "carrier": "c"},
...                  {"type": "mesh", "between": ["p", "r"], "carrier": "c"},
...                  {"type": "fixed", "between": ["r", 0]}],
...        "ports": [{"component": "s", "role": "input"}, {"component": "c", "role": "output"}]}
>>> [c.code for c in model_from_dict(doc).warnings]
['coaxiality', 'assembly']
"""
from __future__ import annotations

import math
from collections import defaultdict
from typing import Any

import numpy as np

from powergraph.errors import Caveat
from powergraph.gears import planetary
from powergraph.model.feasibility_axes import (coaxiality, gear_module, geometry_modules,
                                               mesh_geometry, mesh_centre,
                                               rings_without_carrier, stated_only)


class PlanetarySet:
    """The meshes on one carrier body, split into planets and central gears (filled in
    place while the links are read)."""

    __slots__ = ("carrier", "meshes", "planets", "central", "by_body")

    def __init__(self, carrier: str) -> None:
        self.carrier = carrier
        self.meshes: list = []
        self.planets: set = set()      # planet bodies
        self.central: set = set()      # central gear ids
        self.by_body: dict = {}        # planet body -> its meshes in the set


def feasibility_caveats(model: Any) -> tuple[Caveat, ...]:
    """Every feasibility caveat of ``model`` (a :class:`~powergraph.model.spec.Model`).

    Linear in the size of the model; nothing is checked where the model gives too little
    to decide (a mesh by ``ratio``, a planet without a central mesh).

    Examples
    --------
    See the module's docstring; docs/feasibility.md lists the rules.
    """
    caveats: list[Caveat] = []
    sets = _planetary_sets(model)
    phased = {model.body_of[link.carrier] for link in model.meshes}   # bodies carrying a mesh
    modules = geometry_modules(model)
    for pset in sets.values():
        caveats += _set_caveats(model, pset, phased, modules)
    carriers = _planet_carrier(model, sets)
    caveats += carriers
    caveats += rings_without_carrier(model, {c.path.split(".")[0] for c in carriers})
    caveats += _gear_profiles(model)
    caveats += _undercut(model)
    return tuple(caveats)


# --- reading the sets ---------------------------------------------------------------------
def _planetary_sets(model: Any) -> dict[str, PlanetarySet]:
    """Per carrier body, the set of meshes and its planet bodies (see the module)."""
    coupled = {model.body_of[x] for link in model.links if link.type == "coupling"
               for x in link.between}
    sets: dict[str, PlanetarySet] = {}
    for link in model.meshes:
        body = model.body_of[link.carrier]
        if model.components[link.carrier].count > 1:
            continue                                     # a crank: eccentric, not 2K-H
        if body not in sets:
            sets[body] = PlanetarySet(body)
        sets[body].meshes.append(link)
    for pset in sets.values():
        for link in pset.meshes:
            a, b = model.components[link.between[0]], model.components[link.between[1]]
            for gear, other in ((a, b), (b, a)):
                if gear.count > 1 or (other.internal and not gear.internal):
                    pset.planets.add(model.body_of[gear.id])
        pset.planets -= coupled
        if not pset.planets:
            continue
        pset.central = {x for link in pset.meshes for x in link.between
                        if model.body_of[x] not in pset.planets
                        and model.body_of[x] not in coupled}
        for link in pset.meshes:
            for body in {model.body_of[x] for x in link.between} & pset.planets:
                pset.by_body.setdefault(body, []).append(link)
    held = model.frame_body       # a moving carrier's set first: a planet's home (below)
    return dict(sorted(((body, s) for body, s in sets.items() if s.planets),
                       key=lambda item: item[0] == held))


def _toothed(link: Any, model: Any) -> bool:
    return link.ratio is None and all(model.components[x].teeth for x in link.between)


def _central_meshes(model: Any, pset: PlanetarySet, body: str) -> list[tuple]:
    """``(link, central gear, planet gear)`` of the planet body's meshes with central gears."""
    out = []
    for link in pset.by_body.get(body, ()):
        if not _toothed(link, model):
            continue
        a, b = link.between
        for gear, other in ((a, b), (b, a)):
            if model.body_of[gear] == body and other in pset.central:
                out.append((link, model.components[other], model.components[gear]))
    return out


def _set_caveats(model: Any, pset: PlanetarySet, phased: set, modules: dict
                 ) -> list[Caveat]:
    caveats: list[Caveat] = []
    wrong_rings: set[str] = set()
    centres: dict[str, tuple[float, float | None]] = {}
    for body in sorted(pset.planets):
        meshes = _central_meshes(model, pset, body)
        found, teeth, mm = coaxiality(meshes, modules)
        caveats += found
        if any(c.code == "ring-not-internal" for c in found):
            wrong_rings.add(body)
        if teeth is not None and not found:
            centres[body] = (teeth, mm)
            caveats += _clearance(model, pset, body, teeth, mm)
    caveats += _planets_meet(model, pset, centres, modules)
    for cluster in _clusters(model, pset):
        if not wrong_rings.intersection(cluster):
            caveats += _assembly(model, pset, cluster, bool(phased.intersection(cluster)))
    return caveats


def _planets_meet(model: Any, pset: PlanetarySet, centres: dict, modules: dict
                  ) -> list[Caveat]:
    """Two meshing planets on their centre distances from the axis can reach each other
    (:func:`planetary.planets_meet`): in mm when all three distances are known."""
    out, seen = [], set()
    for body in sorted(centres):
        for link in pset.by_body.get(body, ()):
            a, b = (model.components[x] for x in link.between)
            ba, bb = model.body_of[a.id], model.body_of[b.id]
            if link.index in seen or ba == bb or bb not in centres or ba not in centres \
                    or not _toothed(link, model):
                continue
            seen.add(link.index)
            pair = mesh_centre(link, a, b, modules)
            (ta, ma), (tb, mb) = centres[ba], centres[bb]
            mm = None not in (ma, mb, pair.mm)
            da, db, reach = (ma, mb, pair.mm) if mm else (ta, tb, pair.teeth)
            if planetary.planets_meet(da, db, reach, 0):
                continue
            unit = "mm" if mm else "half-modules"
            out.append(Caveat(
                f"planets {a.id} ({a.teeth}) and {b.id} ({b.teeth}) cannot mesh: their axes "
                f"are {da:.4g} and {db:.4g} {unit} from the central axis, so their centre "
                f"distance {reach:.4g} must lie between |{da:.4g} − {db:.4g}| = "
                f"{abs(da - db):.4g} and {da + db:.4g}", link.path, "coaxiality"))
    return out


# --- neighbours and assembly --------------------------------------------------------------
def _planet_gears(model: Any, pset: PlanetarySet, body: str) -> list:
    gears = {x for link in pset.by_body.get(body, ()) for x in link.between
             if model.body_of[x] == body}
    return [model.components[x] for x in sorted(gears)]


def _clearance(model: Any, pset: PlanetarySet, body: str, teeth: float,
               mm: float | None) -> list[Caveat]:
    """Tip circles of neighbouring planets clear: ``d_a < 2 a sin(π/n)`` — in mm when the
    centre distance and the gear's module are known, else in modules (``z + 2 h_a*``)."""
    out = []
    for gear in _planet_gears(model, pset, body):
        n = gear.count
        if n < 2 or not gear.teeth:
            continue
        module, tip = _tip(gear, pset.by_body.get(body, ()), model)
        if mm is not None and module is not None:
            size, unit, span = module, "mm", 2 * mm
        else:
            size, unit, span = 1.0, "modules", teeth
        diameter = size * (gear.teeth + 2 * tip)
        if planetary.neighbours_clear(np.array(size * gear.teeth), np.array(span), n,
                                      2 * tip * size):
            continue
        room = span * math.sin(math.pi / n)
        centre = f"{mm:.4g} mm" if unit == "mm" else f"{teeth:g} half-modules"
        out.append(Caveat(
            f"{n} planets of {gear.teeth} teeth on a centre distance of {centre}: tip "
            f"diameter {diameter:.4g} {unit} ≥ 2·a·sin(π/{n}) = {room:.4g} {unit} between "
            "neighbouring axes: neighbouring planets collide",
            f"components.{gear.raw_id}.count", "planet-clearance"))
    return out


def _tip(gear: Any, links: Any, model: Any) -> tuple[float | None, float]:
    """Module and ``h_a* + x`` of ``gear``: from a mesh geometry that names it (unshifted
    when it gives a ``centre_distance`` and no shifts), else its own geometry's module and
    an unshifted addendum of one module."""
    for link in links:
        g = mesh_geometry(link)
        if g is not None and gear.id in link.between:
            return g.module, g.addendum + (_shift(g, gear.id, link, model) or 0.0)
    return gear_module(gear), 1.0


def _shift(g: Any, gear: str, link: Any, model: Any) -> float | None:
    """The profile shift a mesh geometry gives ``gear``: None without shifts (a
    ``centre_distance`` alone)."""
    if stated_only(g):
        return None
    return g.shift_1 if _pinion(link, model) == gear else g.shift_2


def _pinion(link: Any, model: Any) -> str:
    """The gear a mesh geometry names first: the external one of an internal pair, the
    link's first gear otherwise."""
    return sorted(link.between, key=lambda x: model.components[x].internal)[0]


def _clusters(model: Any, pset: PlanetarySet) -> list[list[str]]:
    """Planet bodies joined by planet-planet meshes (each body alone otherwise)."""
    parent = {body: body for body in pset.planets}

    def find(x: str) -> str:
        while parent[x] != x:
            x = parent[x]
        return x

    for link in pset.meshes:
        a, b = (model.body_of[x] for x in link.between)
        if a in parent and b in parent:
            parent[find(a)] = find(b)
    groups: dict[str, list[str]] = defaultdict(list)
    for body in sorted(pset.planets):
        groups[find(body)].append(body)
    return list(groups.values())


def _assembly(model: Any, pset: PlanetarySet, cluster: list[str], phased: bool
              ) -> list[Caveat]:
    """Equal-spacing assembly of one planet cluster (:func:`planetary.assembles`)."""
    gears = [g for body in cluster for g in _planet_gears(model, pset, body)]
    counts = {g.count for g in gears}
    if len(counts) != 1 or not all(g.teeth for g in gears):
        return []
    (n,) = counts
    members = set(cluster)
    links = {link.index: link for body in cluster for link in pset.by_body.get(body, ())}
    pp = [(model.body_of[a], model.body_of[b], model.components[a].teeth,
           model.components[b].teeth) for link in links.values() if _toothed(link, model)
          for a, b in [link.between]
          if model.body_of[a] in members and model.body_of[b] in members]
    turns = planetary.relative_turns(cluster[0], pp)
    if len(turns) != len(cluster):
        return []
    common = math.prod(den for _, den in turns.values())
    central, coefficients = [], []
    for body in cluster:
        num, den = turns[body]
        for link, gear, planet in _central_meshes(model, pset, body):
            sign = 1 if gear.internal else -1
            central.append(gear)
            coefficients.append(sign * planet.teeth * num * (common // den))
    if len(central) < (1 if phased else 2):
        return []
    z = [np.array([g.teeth]) for g in central]
    a = [np.array([c]) for c in coefficients]
    if planetary.assembles(z, a, n, phased)[0]:
        return []
    planet = next(g for g in gears if g.count == n)
    return [Caveat(_assembly_words(central, coefficients, n, phased),
                   f"components.{planet.raw_id}.count", "assembly")]


def _assembly_words(central: list, coefficients: list[int], n: int, phased: bool) -> str:
    names = ", ".join(f"{'ring' if g.internal else 'sun'} {g.id} ({g.teeth})" for g in central)
    tail = f"{n} planets cannot be assembled at equal spacing"
    if phased:
        bad = [g for g in central if g.teeth % n]
        return ("the planets carry another stage, so every copy is identical: "
                + ", ".join(f"{g.teeth}/{n} = {g.teeth / n:.4g}" for g in bad)
                + f" is not whole: {tail}")
    if len(central) == 2:
        (z1, z2), (a1, a2) = [g.teeth for g in central], coefficients
        if a1 == -a2:                         # a simple planet between sun and ring
            return f"({z1} + {z2})/{n} = {(z1 + z2) / n:.4g} is not whole ({names}): {tail}"
        if a1 == a2:                          # a double planet between sun and ring
            big, small = max(z1, z2), min(z1, z2)
            return (f"({big} − {small})/{n} = {(big - small) / n:.4g} is not whole ({names}): "
                    f"{tail}")
        value = (a2 * z1 - a1 * z2) / (n * math.gcd(a1, a2))
        return (f"({a2}·{z1} − ({a1})·{z2})/({n}·gcd({a1}, {a2})) = {value:.4g} is not whole "
                f"({names}): {tail}")
    return f"no turn of the planets fits every central gear ({names}) at once: {tail}"


# --- carriers and undercut ----------------------------------------------------------------
def _planet_carrier(model: Any, sets: dict[str, PlanetarySet]) -> list[Caveat]:
    """A planet's gears mesh only on its own carrier (or on a body held with it). A
    planet's home is its first set, a moving carrier's before the frame's."""
    home: dict[str, tuple[str, Any]] = {}
    for body, pset in sets.items():
        for link in pset.meshes:
            for x in link.between:
                if model.body_of[x] in pset.planets:
                    home.setdefault(model.body_of[x], (body, link))
    out = []
    for link in model.meshes:
        carrier = model.body_of[link.carrier]
        for x in link.between:
            planet = model.body_of[x]
            if planet in home and home[planet][0] != carrier:
                other = home[planet][1]
                out.append(Caveat(
                    f"planet {x} meshes here on carrier {link.carrier}"
                    f"{' (fixed axes)' if link.carrier == model.frame else ''} but on carrier "
                    f"{other.carrier} in {other.path}: a planet's axis turns with its own "
                    f"carrier; write carrier: {model.raw_id(other.carrier)}",
                    f"{link.path}.carrier", "planet-carrier"))
                break
    return out


def _gear_profiles(model: Any) -> list[Caveat]:
    """A gear meshing twice has one profile: every mesh geometry naming it (and its own
    ``geometry``'s module) gives it the same module, pressure angle, |helix angle|,
    addendum and shift (a ``centre_distance`` without shifts gives no shift)."""
    seen: dict[str, dict[str, tuple[float, str]]] = {}
    for component in model.components.values():
        module = gear_module(component)
        if module is not None:
            seen[component.id] = {"module": (module, f"components.{component.raw_id}"
                                                     ".geometry")}
    out = []
    for link in model.meshes:
        g = mesh_geometry(link)
        if g is None:
            continue
        for gear in link.between:
            values = {"module": g.module, "pressure angle": g.pressure_angle_deg,
                      "helix angle": abs(g.helix_angle_deg), "addendum": g.addendum,
                      "shift": _shift(g, gear, link, model)}
            known = seen.setdefault(gear, {})
            for name, value in values.items():
                if value is None:
                    continue
                if name not in known:
                    known[name] = (value, f"{link.path}.geometry")
                elif not math.isclose(value, known[name][0], rel_tol=1e-9, abs_tol=1e-12):
                    out.append(Caveat(
                        f"gear {gear} has {name} {known[name][0]:g} in {known[name][1]} "
                        f"but {value:g} here: one gear has one tooth profile (module, "
                        "pressure angle, helix, addendum and profile shift)",
                        f"{link.path}.geometry", "gear-profile"))
                    break
    return out


def _undercut(model: Any) -> list[Caveat]:
    """External gears of a mesh with a ``geometry`` block, cut by a rack: ``z`` below
    ``2 (h_a* − x) cos β / sin² α_t`` teeth is undercut. A ``centre_distance`` without
    shifts: undercut when no split of its shift sum that meshes avoids it (one caveat)."""
    out = []
    for link in model.meshes:
        g = mesh_geometry(link)
        if g is None:
            continue
        first = _pinion(link, model)
        second = link.between[1] if first == link.between[0] else link.between[0]
        names = {1: first, 2: second}
        if stated_only(g):                       # a centre_distance without shifts
            found = planetary.undercut_gears(g.split)
            if found:
                side, z, limit = found[0]
                what = "x2 − x1" if g.internal else "x1 + x2"
                out.append(Caveat(
                    f"every split of the shift sum {what} = {g.shift_sum:.4f} that puts the "
                    f"pair at its centre_distance {g.centre_distance:g} mm and meshes leaves "
                    f"a gear undercut by a rack (e.g. shifts {g.split.shift_1:g}, "
                    f"{g.split.shift_2:.4g}: gear {names[side]}, {z} teeth, needs "
                    f"{limit:.4g} at that shift)", f"{link.path}.geometry", "undercut"))
            continue
        for side, z, limit in planetary.undercut_gears(g):
            gear, x = names[side], (g.shift_1 if side == 1 else g.shift_2)
            need = g.addendum - z / planetary.undercut_limit(
                g.pressure_angle_deg, 0.0, 1.0, g.helix_angle_deg)
            out.append(Caveat(
                f"gear {gear} ({z} teeth, shift {x:g}) is undercut when cut by a rack: "
                f"fewer than 2·(h_a* − x)·cos β/sin²α_t = {limit:.4g} teeth at "
                f"{g.pressure_angle_deg:g}°; give it a shift of at least {need:.3f}",
                f"{link.path}.geometry", "undercut"))
    return out
