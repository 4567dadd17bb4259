"""Optional analysis blocks in model files; their format is part of the model schema
(:mod:`powergraph.model.schema`), their semantic checks live in one module each:

- ``components.ID.geometry`` (volume, docs/volume.md): :mod:`powergraph.model.block_geometry`
  (its shapes; read by :func:`validate_geometry` here, after the schema's format)
- ``links[i].backlash`` / ``links[i].backlash_arcmin`` (docs/backlash.md):
  :mod:`powergraph.model.block_backlash`
- ``links[i].cycloid`` (docs/cycloid.md): :mod:`powergraph.model.block_cycloid`
- ``links[i].friction`` with ``links[i].geometry`` (docs/losses.md), or ``geometry`` alone
  (the pair's involute geometry for the feasibility checks, docs/feasibility.md):
  :mod:`powergraph.model.block_friction`
- ``links[i].pins`` (+ ``output_pins``, ``crank_bearing``) on a cycloid mesh
  (docs/losses.md): :mod:`powergraph.model.block_pins`, stored as the mesh's friction law
- top-level ``tolerances`` (PATH -> distribution, docs/tolerance.md):
  :mod:`powergraph.model.block_tolerances`

The model layer validates them (so ``powergraph check`` catches every mistake) and stores
the result; the analyses read them.
"""
from __future__ import annotations

from dataclasses import fields
from typing import Any, Mapping

from powergraph.errors import ModelError
from powergraph.model.spec import Component
from powergraph.model.units import parse_quantity


def validate_geometry(raw: Any, path: str, teeth: int | None = None) -> Any:
    """Validate a component's ``geometry`` block into an immutable dataclass.

    The block's format (shapes, keys, types, ranges) is checked against the model schema
    (:mod:`powergraph.model.schema`); then the dimension checks of its shape's class
    (:mod:`powergraph.model.block_geometry`) run. A block without ``shape`` on a component
    with teeth is a gear.

    Parameters
    ----------
    raw : dict
        The block as read from YAML: ``shape`` plus that shape's parameters.
    path : str
        Place in the model file (``components.1.geometry``), for error messages.
    teeth : int, optional
        The component's tooth number, when the caller has it: enables the checks that need
        it (gear bore inside the root circle, pins not overlapping). The volume analysis
        runs them again in any case.

    Returns
    -------
    GearGeometry, CycloidDiscGeometry, NeedleGearGeometry, CrankshaftGeometry,
    PlanetFrame1Geometry or PlanetFrame2Geometry

    Raises
    ------
    ModelError
        Unknown shape, unknown or missing key, a value of the wrong type or sign, or
        dimensions that cannot be built; the path names the key.

    Examples
    --------
    >>> g = validate_geometry({"shape": "crankshaft", "shaft_radius": 10,
    ...     "gear_seat_length": 12, "bearing_width": 10, "journal_radius": 13,
    ...     "journal_length": 10, "journals": 2}, "components.3.geometry")
    >>> g.journals, g.to_dict()["shape"]
    (2, 'crankshaft')
    >>> validate_geometry({"module": 2, "face_width": 10, "bore_radius": 5},
    ...                   "components.1.geometry", teeth=30).shape
    'gear'
    """
    from powergraph.model.block_geometry import SHAPES
    from powergraph.model.conform import conform, definition

    if isinstance(raw, dict) and "shape" not in raw and teeth is None:
        raise ModelError(f"missing: say which formula applies (one of {', '.join(SHAPES)}); "
                         "it may be left out only on a component with teeth (a gear)",
                         f"{path}.shape")
    conform(raw, definition("geometry"), path)
    cls = SHAPES[raw.get("shape", "gear")]
    geometry = cls(**{spec.name: _value(raw[spec.name], spec, f"{path}.{spec.name}")
                      for spec in fields(cls)})
    geometry.check(path)
    if teeth is not None:
        geometry.check_teeth(teeth, path)
    return geometry


def _value(raw: Any, spec: Any, path: str) -> Any:
    """A schema-checked value as its field's type (lengths in mm, counts, ids as text)."""
    kind = spec.metadata["kind"]
    if kind == "component":
        return str(raw)
    if kind == "count":
        return raw
    return parse_quantity(raw, "length", path)


def validate_mesh_blocks(raw: Mapping, path: str, pair: tuple[str, str],
                         components: Mapping[str, Component]) -> dict[str, Any]:
    """Validate the analysis blocks a mesh link carries; returns ``{name: block}``."""
    blocks: dict[str, Any] = {}
    if "backlash" in raw or "backlash_arcmin" in raw:
        from powergraph.model.block_backlash import validate_backlash

        blocks.update(validate_backlash(raw, path, pair, components))
    if "cycloid" in raw:
        from powergraph.model.block_cycloid import validate_cycloid

        blocks["cycloid"] = validate_cycloid(raw["cycloid"], f"{path}.cycloid", pair, components)
    pins = any(key in raw for key in ("pins", "output_pins", "crank_bearing"))
    if "geometry" in raw and "friction" not in raw:
        if pins or "cycloid" in raw:
            raise ModelError("a cycloid mesh takes no involute geometry (its pins block or "
                             "the disc's geometry gives its dimensions)", f"{path}.geometry")
        from powergraph.model.block_friction import parse_mesh_geometry

        gears = tuple((g, components[g].teeth, components[g].internal) for g in pair)
        blocks["geometry"] = parse_mesh_geometry(raw["geometry"], gears, path)
    if "friction" in raw and "efficiency" in raw:
        raise ModelError("give the mesh's efficiency or its friction, not both (the "
                         "friction law sets the efficiency)", f"{path}.efficiency")
    if pins:
        from powergraph.model.block_pins import parse_pins

        blocks["friction"] = parse_pins(raw, path, pair, components)   # docs/losses.md
    elif "friction" in raw:
        from powergraph.model.block_friction import parse_mesh_friction

        gears = tuple((g, components[g].teeth, components[g].internal) for g in pair)
        blocks["friction"] = parse_mesh_friction(int(path[6:-1]), raw["friction"],
                                                 raw.get("geometry"), gears, path)
    return blocks


def validate_tolerances(raw: Any, model) -> Any:
    """Validate the top-level ``tolerances:`` block against the built model (its PATHs
    address the model's values; see :mod:`powergraph.model.block_tolerances`)."""
    from powergraph.model.block_tolerances import validate_tolerances as validate

    return validate(raw, model)
