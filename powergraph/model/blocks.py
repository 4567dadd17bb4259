"""Optional analysis blocks in model files; their format is part of the model schema
(:mod:`powergraph.model.schema`), their semantic checks live in one module each:

- ``components.ID.geometry`` (volume, docs/volume.md): :mod:`powergraph.model.block_geometry`
- ``links[i].backlash`` / ``links[i].backlash_arcmin`` (docs/backlash.md):
  :mod:`powergraph.model.block_backlash`
- ``links[i].cycloid`` (docs/cycloid.md): :mod:`powergraph.model.block_cycloid`

The model layer validates them (so ``powergraph check`` catches every mistake) and stores
the result; the analyses read them.
"""
from __future__ import annotations

from typing import Any, Mapping

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
    return blocks
