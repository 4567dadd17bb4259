"""A mesh's ``backlash:`` block and ``backlash_arcmin:`` value (Li et al. 2012).

A mesh link may carry either

- ``backlash_arcmin: 3.5`` -- the angular play of the mesh's *first* gear (``between[0]``)
  with the second held, in the carrier's frame, in arc-minutes; or
- ``backlash:`` -- the measurements of Li et al. (2012) for an internal involute pair, from
  which :mod:`powergraph.analyses.backlash` computes the equivalent profile shifts, the
  eccentric offset and the lost motion::

      backlash:
        module: 1                    # mm
        pressure_angle: 20           # degrees (default 20)
        pin_diameter: 1.732          # mm
        standard_M: {ring: 42.434, pinion: 42.436}
        measured_M: {ring: [42.485, 42.481], pinion: [42.401, 42.398]}
        runout: {ring: 0.022, pinion: 0.015}      # F_r, mm (default 0)
        bearing_clearance: [0.005, 0.006]         # u_r of each bearing, mm (default none)
        assembly: standard           # or "compensated" (eccentric at a''); default standard

  The ids in ``standard_M``, ``measured_M`` and ``runout`` must be exactly the two gears of
  the mesh, one internal and one external, both with ``teeth``. Lengths are numbers in mm
  or strings with a length unit (``"5 um"``). Types and ranges are checked against the
  model schema (:mod:`powergraph.model.schema`); this module checks what depends on the
  mesh: the gears' ids, roles and tooth counts, and that each over-pin distance is possible.

Examples
--------
>>> from powergraph.model import model_from_dict
>>> block = {"module": 1, "pin_diameter": 1.732,
...          "standard_M": {5: 42.434, 4: 42.436},
...          "measured_M": {5: [42.479, 42.481], 4: [42.404]}}
>>> m = model_from_dict({"name": "pair",
...     "components": {0: {"role": "frame"}, 4: {"teeth": 40}, 5: {"teeth": 45, "internal": True},
...                    9: {}},
...     "links": [{"type": "mesh", "between": [4, 5], "carrier": 9, "backlash": block}],
...     "ports": [{"component": 9, "role": "input"}, {"component": 4, "role": "output"}]})
>>> b = m.links[0].blocks["backlash"]
>>> b.internal, b.external, b.pressure_angle, b.measured_M["5"]
('5', '4', 20.0, (42.479, 42.481))
"""
from __future__ import annotations

import math
from dataclasses import field
from types import MappingProxyType
from typing import Any, Mapping

from powergraph.errors import ModelError
from powergraph.model.units import parse_quantity
from powergraph.records import record


@record
class BacklashBlock:
    """A validated ``backlash:`` block (lengths in mm, angle in degrees).

    ``internal`` and ``external`` are the ids (strings) of the pair's two gears; the three
    mappings are keyed by those ids. ``assembly`` says where the pair is assembled:
    ``"standard"`` (standard centre distance) or ``"compensated"`` (eccentric at a'').
    """

    module: float
    pin_diameter: float
    internal: str
    external: str
    standard_M: Mapping[str, float]
    measured_M: Mapping[str, tuple[float, ...]]
    runout: Mapping[str, float] = field(default_factory=dict)
    bearing_clearance: tuple[float, ...] = ()
    pressure_angle: float = 20.0
    assembly: str = "standard"

    def __post_init__(self) -> None:
        for name in ("standard_M", "measured_M", "runout"):
            value = {str(k): v for k, v in getattr(self, name).items()}
            if name == "measured_M":
                value = {k: tuple(float(x) for x in v) for k, v in value.items()}
            object.__setattr__(self, name, MappingProxyType(value))
        object.__setattr__(self, "bearing_clearance", tuple(self.bearing_clearance))

    def to_dict(self) -> dict:
        return {"module": self.module, "pressure_angle": self.pressure_angle,
                "pin_diameter": self.pin_diameter, "standard_M": dict(self.standard_M),
                "measured_M": {k: list(v) for k, v in self.measured_M.items()},
                "runout": dict(self.runout), "bearing_clearance": list(self.bearing_clearance),
                "assembly": self.assembly}


def validate_backlash(raw: Mapping, path: str, pair: tuple, components: Mapping) -> dict:
    """Validate a mesh link's ``backlash`` / ``backlash_arcmin`` fields.

    Parameters
    ----------
    raw : mapping
        The whole link as written in the file.
    path : str
        The link's place in the file (``links[3]``).
    pair : tuple of str
        The mesh's two gear ids.
    components : mapping
        ``{id: Component}`` of the model.

    Returns
    -------
    dict
        ``{"backlash": BacklashBlock}`` and/or ``{"backlash_arcmin": float}``.
    """
    blocks: dict[str, Any] = {}
    if "backlash" in raw and "backlash_arcmin" in raw:
        raise ModelError("give either backlash or backlash_arcmin on a mesh, not both",
                         f"{path}.backlash_arcmin")
    if "backlash_arcmin" in raw:
        blocks["backlash_arcmin"] = float(raw["backlash_arcmin"])
    if "backlash" in raw:
        blocks["backlash"] = _block(raw["backlash"], f"{path}.backlash", pair, components)
    return blocks


def _roles(pair: tuple, components: Mapping, path: str) -> tuple[str, str]:
    """(internal id, external id) of the mesh, or a ModelError."""
    for gear in pair:
        if components[gear].teeth is None:
            raise ModelError(f"gear {gear!r} has no teeth; the over-pin (M) equations need "
                             "both gears' tooth counts", path)
    internal = [g for g in pair if components[g].internal]
    if len(internal) != 1:
        raise ModelError("this block is for an internal pair: exactly one of the two gears "
                         f"must be internal, found {len(internal)}", path)
    external = next(g for g in pair if g != internal[0])
    if components[internal[0]].teeth <= components[external].teeth:
        raise ModelError(f"the internal gear {internal[0]!r} must have more teeth than the "
                         f"external gear {external!r}", path)
    return internal[0], external


def _length(value: Any, path: str) -> float:
    return parse_quantity(value, "length", path)


def _lengths(value: Any, path: str) -> tuple[float, ...]:
    """One length or a list of them (already checked by the schema)."""
    if isinstance(value, list):
        return tuple(_length(v, f"{path}[{i}]") for i, v in enumerate(value))
    return (_length(value, path),)


def _block(raw: dict, path: str, pair: tuple, components: Mapping) -> BacklashBlock:
    internal, external = _roles(pair, components, path)
    module, pin = _length(raw["module"], f"{path}.module"), _length(raw["pin_diameter"],
                                                                      f"{path}.pin_diameter")
    alpha = float(raw.get("pressure_angle", 20.0))
    standard = _per_gear(raw["standard_M"], f"{path}.standard_M", pair, _length)
    measured = _per_gear(raw["measured_M"], f"{path}.measured_M", pair, _lengths)
    runout = _per_gear(raw.get("runout", {g: 0.0 for g in pair}), f"{path}.runout", pair,
                       _length)
    bearings = _lengths(raw["bearing_clearance"], f"{path}.bearing_clearance") \
        if "bearing_clearance" in raw else ()
    geometry = {"module": module, "alpha": math.radians(alpha), "pin": pin}
    for gear, value in standard.items():
        _check_pin_circle(value, components[gear], geometry, f"{path}.standard_M.{gear}")
    for gear, values in measured.items():
        for i, value in enumerate(values):
            _check_pin_circle(value, components[gear], geometry, f"{path}.measured_M.{gear}[{i}]")
    return BacklashBlock(module=module, pressure_angle=alpha, pin_diameter=pin,
                         internal=internal, external=external, standard_M=standard,
                         measured_M=measured, runout=runout, bearing_clearance=bearings,
                         assembly=raw.get("assembly", "standard"))


def _per_gear(raw: dict, path: str, pair: tuple, convert) -> dict:
    """A mapping {gear id: value} over exactly the mesh's two gears."""
    out = {}
    for key, value in raw.items():
        gear = str(key)
        if isinstance(key, bool) or gear not in pair:
            raise ModelError(f"{key!r} is not a gear of this mesh (the gears are {pair[0]!r} "
                             f"and {pair[1]!r})", f"{path}.{key}")
        if gear in out:
            raise ModelError(f"gear {gear!r} is given twice (ids compare as strings)",
                             f"{path}.{key}")
        out[gear] = convert(value, f"{path}.{key}")
    for gear in pair:
        if gear not in out:
            raise ModelError("missing (give a value for each gear of the mesh)",
                             f"{path}.{gear}")
    return out


def _check_pin_circle(m_value: float, gear, geometry: Mapping, path: str) -> None:
    """The pin centres must lie outside the base circle (Eqs. 12-13 need cos a_M < 1)."""
    module, alpha, pin = geometry["module"], geometry["alpha"], geometry["pin"]
    z = gear.teeth
    odd = math.cos(math.pi / (2 * z)) if z % 2 else 1.0
    across = m_value + pin if gear.internal else m_value - pin
    base = module * z * math.cos(alpha) * odd
    if across <= base:
        side = "+" if gear.internal else "-"
        raise ModelError(f"over-pin distance {m_value:g} mm is impossible for gear {gear.id!r} "
                         f"(z = {z}, module {module:g}): M {side} pin diameter must exceed the "
                         f"base diameter{' x cos(90/z)' if z % 2 else ''} = {base:.4f} mm", path)
