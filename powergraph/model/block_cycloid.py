"""Schema of a mesh's ``cycloid`` block (placeholder until seeds/003 lands)."""
from __future__ import annotations

from types import MappingProxyType
from typing import Any, Mapping

from powergraph.errors import ModelError


def validate_cycloid(raw: Any, path: str, pair: tuple, components: Mapping) -> Any:
    if not isinstance(raw, dict):
        raise ModelError("must be a mapping", path)
    return MappingProxyType(dict(raw))
