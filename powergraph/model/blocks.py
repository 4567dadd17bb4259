"""Optional analysis blocks in model files; their format is part of the model schema
(:mod:`powergraph.model.schema`), their semantic checks live in one module each:

- ``components.ID.geometry`` (volume, docs/volume.md): :mod:`powergraph.model.block_geometry`
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

from typing import Any, Mapping

from powergraph.errors import ModelError
from powergraph.model.spec import Component


def validate_geometry(raw: Any, path: str, teeth: int | None = None) -> Any:
    """Validate a component's ``geometry`` block (see :mod:`.block_geometry`); the
    component's teeth let checks such as "bore inside the root circle" run at load time."""
    from powergraph.model.block_geometry import validate_geometry as validate

    return validate(raw, path, teeth=teeth)


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
