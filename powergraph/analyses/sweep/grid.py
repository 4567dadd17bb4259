"""``PATH=START:STOP:N`` settings and the Cartesian grid of several of them (the CLI's
``--set``)."""
from __future__ import annotations

import re
from typing import Sequence

import numpy as np

from powergraph.analyses.sweep.paths import PORT_FIELDS, parse_path
from powergraph.errors import ModelError, UsageError
from powergraph.model.spec import Model

#: Largest grid the CLI builds (variants).
MAX_VARIANTS = 50_000_000


def parse_set(model: Model, text: str) -> tuple[str, np.ndarray]:
    """Parse one ``PATH=START:STOP:N`` (N evenly spaced values, ends included).

    ``PATH=V1,V2,...`` (a list) and ``PATH=V`` (one value) are accepted too. Port speeds,
    powers and torques may carry units (``ports.0.speed=1000rpm:3000rpm:5``). Tooth
    numbers must come out whole.

    Raises
    ------
    UsageError
        Bad syntax (no ``=``, N not a whole number >= 1, a value that is not a number).
    ModelError
        A PATH the model does not have, or teeth that would not be whole numbers.

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> rv = load_model("models/rv40e.yaml")
    >>> parse_set(rv, "components.5.teeth=38:42:5")[1].tolist()
    [38.0, 39.0, 40.0, 41.0, 42.0]
    >>> parse_set(rv, "links.1.efficiency=0.9,0.95,1")[1].tolist()
    [0.9, 0.95, 1.0]
    """
    path, sep, spec = text.partition("=")
    path, spec = path.strip(), spec.strip()
    if not sep or not path or not spec:
        raise UsageError(f"--set {text!r}: expected PATH=START:STOP:N "
                         "(e.g. links.1.efficiency=0.9:1:11)")
    param = parse_path(model, path)
    if ":" in spec:
        values = _range(text, spec, param.kind, path)
    else:
        values = np.array([_number(text, item, param.kind, path) for item in spec.split(",")])
    if param.kind == "teeth":
        values = _whole(text, values, path)
    return path, values


def _range(text: str, spec: str, kind: str, path: str) -> np.ndarray:
    parts = spec.split(":")
    if len(parts) != 3:
        raise UsageError(f"--set {text!r}: a range is START:STOP:N (three fields)")
    start, stop = (_number(text, p, kind, path) for p in parts[:2])
    if not re.fullmatch(r"\s*\d+\s*", parts[2]) or int(parts[2]) < 1:
        raise UsageError(f"--set {text!r}: N must be a whole number >= 1, got {parts[2]!r}")
    count = int(parts[2])
    if count == 1 and start != stop:
        raise UsageError(f"--set {text!r}: N = 1 needs START = STOP")
    return np.linspace(start, stop, count)


def _number(text: str, item: str, kind: str, path: str) -> float:
    item = item.strip()
    try:
        return float(item)
    except ValueError:
        pass
    if kind in PORT_FIELDS and item:
        from powergraph.model.units import parse_quantity

        try:
            return parse_quantity(item, kind, path)
        except ModelError as exc:
            raise UsageError(f"--set {text!r}: {exc.message}") from None
    raise UsageError(f"--set {text!r}: {item!r} is not a number")


def _whole(text: str, values: np.ndarray, path: str) -> np.ndarray:
    rounded = np.round(values)
    off = np.abs(values - rounded) > 1e-9
    if np.any(off):
        raise ModelError(f"teeth must be whole numbers, but --set {text!r} gives "
                         f"{values[off][0]:g}; choose START, STOP and N so that the step "
                         "(STOP - START)/(N - 1) is whole", path)
    return rounded


def parse_sets(model: Model, texts: Sequence[str]) -> dict[str, np.ndarray]:
    """Parse several ``--set`` texts; a PATH may appear only once."""
    out: dict[str, np.ndarray] = {}
    for text in texts:
        path, values = parse_set(model, text)
        if path in out:
            raise UsageError(f"--set {path} is given twice")
        out[path] = values
    return out


def cartesian(sets: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """The Cartesian grid of several value lists, as open (broadcastable) arrays.

    The first PATH varies slowest; the sweep's arrays then have shape
    ``(N1, N2, ...)`` and its CSV rows follow that order.

    Examples
    --------
    >>> g = cartesian({"a": np.array([1.0, 2.0]), "b": np.array([3.0, 4.0, 5.0])})
    >>> g["a"].shape, g["b"].shape
    ((2, 1), (1, 3))
    """
    total = int(np.prod([len(v) for v in sets.values()], dtype=np.int64)) if sets else 0
    if total > MAX_VARIANTS:
        raise UsageError(f"the grid has {total:,} variants (more than {MAX_VARIANTS:,}); "
                         "use fewer points")
    grids = np.ix_(*[np.asarray(v, float) for v in sets.values()])
    return dict(zip(sets, grids))
