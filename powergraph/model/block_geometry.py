"""Schema of ``components.ID.geometry`` (placeholder until the volume analysis lands)."""
from __future__ import annotations

from types import MappingProxyType
from typing import Any

from powergraph.errors import ModelError
from powergraph.model.units import parse_quantity


def validate_geometry(raw: Any, path: str) -> Any:
    """Return the geometry block as a read-only mapping of lengths in mm."""
    if not isinstance(raw, dict):
        raise ModelError("geometry must be a mapping", path)
    return MappingProxyType({str(k): parse_quantity(v, "length", f"{path}.{k}")
                             for k, v in raw.items()})
