"""What a sweep varies: checks on the values swept at the PATHs of
:mod:`powergraph.model.paths`, and the ``PATH=START:STOP:N`` settings of the CLI's ``--set``
with their Cartesian grid.
"""
from __future__ import annotations

import math
import re
from types import MappingProxyType
from typing import Any, Mapping, Sequence

import numpy as np

from powergraph.errors import ModelError, UsageError
from powergraph.model.paths import LINK_FIELDS, PORT_FIELDS, Parameter, parse_path
from powergraph.model.schema_parts import (MAX_POWER, MAX_RATIO, MAX_SPEED, MAX_TEETH,
                                           MAX_TORQUE)
from powergraph.model.spec import Model

__all__ = ["LINK_FIELDS", "PORT_FIELDS", "Parameter", "as_array", "broadcast_values",
           "cartesian", "check_all", "check_values", "flat_values", "parse_path",
           "parse_paths", "parse_set", "parse_sets", "shaped_views", "value_allowed"]


def parse_paths(model: Model, paths) -> tuple[Parameter, ...]:
    """Parse several PATHs; the same model value may not be swept twice."""
    params = tuple(parse_path(model, p) for p in paths)
    seen: dict[tuple, str] = {}
    for param in params:
        group = "load" if param.kind in ("power", "torque") else param.kind
        for target in param.targets:
            if (group, target) in seen:
                raise UsageError(f"sweep PATHs {seen[group, target]!r} and {param.path!r} "
                                 "set the same model value")
            seen[group, target] = param.path
    _check_teeth_used(model, params)
    return params


def _check_teeth_used(model: Model, params: tuple[Parameter, ...]) -> None:
    """A swept tooth number must drive some mesh's Willis ratio, or it changes nothing."""
    ratio_swept = {t for p in params if p.kind == "ratio" for t in p.targets}
    for param in params:
        if param.kind != "teeth":
            continue
        cid = param.targets[0]
        used = [link.index for link in model.meshes if cid in link.between
                and link.ratio is None and link.index not in ratio_swept]
        if not used:
            raise ModelError(f"component {cid!r} is in no mesh whose Willis ratio follows "
                             "from the teeth (its meshes give ratio:), so sweeping its teeth "
                             "changes nothing", param.path)


def as_array(param: Parameter, values) -> np.ndarray:
    """The values of one parameter as a numeric array (integer teeth stay integer).

    Raises
    ------
    ModelError
        Values that are not numbers (naming the PATH).
    UsageError
        No values.
    """
    try:
        array = np.asarray(values)
        if array.dtype.kind not in "iu" or param.kind != "teeth":
            array = array.astype(float, copy=False)
    except (TypeError, ValueError):
        raise ModelError(f"values must be numbers, got {values!r}", param.path) from None
    if array.size == 0:
        raise UsageError(f"sweep PATH {param.path!r}: no values given")
    return array


def check_values(param: Parameter, array: np.ndarray) -> np.ndarray:
    """Check the values of one parameter (cheap reductions; the detail only on failure).

    Raises
    ------
    ModelError
        Naming the PATH: teeth that are not whole numbers from 1 to MAX_TEETH, efficiencies
        outside (0, 1], a zero or too large ratio, a speed, power or torque that is not
        finite or beyond the limits of a model file.
    """
    kind = param.kind
    low = np.minimum.reduce(array, axis=None)
    high = np.maximum.reduce(array, axis=None)
    if kind == "teeth":
        ok = 1 <= low and high <= MAX_TEETH and (
            array.dtype.kind in "iu" or np.array_equal(np.floor(array), array))
    elif kind == "efficiency":
        ok = low > 0 and high <= 1
    else:
        limit = MAX_RATIO if kind == "ratio" else _LIMITS.get(kind, np.inf)
        ok = np.isfinite(low) and np.isfinite(high) and -limit <= low and high <= limit and (
            kind != "ratio" or (low > 0 or high < 0 or np.all(array != 0)))
    if not ok:
        bad = _bad_values(kind, np.asarray(array, dtype=float))
        first = np.asarray(array)[bad].flat[0]
        count = int(np.count_nonzero(bad))
        raise ModelError(f"{_rule(kind)}; got {float(first):g}"
                         + (f" ({count} of {array.size} values are out of range)"
                            if count > 1 else ""), param.path)
    return array


def broadcast_values(params: Sequence[Parameter], values: Mapping[str, Any],
                     check: bool = True) -> tuple[dict, tuple[int, ...]]:
    """The checked arrays of exactly the PATHs of ``params``, and their broadcast shape.
    With ``check`` False the values are not range-checked (the caller checks them with
    :func:`check_values`, or proves them allowed by :func:`value_allowed`).

    Raises
    ------
    UsageError
        Not a mapping, missing or unknown PATHs, arrays that do not broadcast.
    ModelError
        A value out of range (named by its PATH).
    """
    paths = [p.path for p in params]
    if not isinstance(values, Mapping):
        raise UsageError("sweep values must be a mapping PATH -> array")
    missing = [p for p in paths if p not in values]
    unknown = [p for p in values if p not in paths]
    if missing or unknown:
        raise UsageError("sweep values must give exactly the compiled PATHs "
                         f"({', '.join(paths)})"
                         + (f"; missing {', '.join(missing)}" if missing else "")
                         + (f"; not compiled: {', '.join(map(str, unknown))}"
                            if unknown else ""))
    arrays = {p.path: as_array(p, values[p.path]) for p in params}
    if check:
        check_all(params, arrays)
    try:
        shape = np.broadcast_shapes(*(a.shape for a in arrays.values()))
    except ValueError:
        shapes = ", ".join(f"{p} {a.shape}" for p, a in arrays.items())
        raise UsageError(f"the swept arrays do not broadcast together: {shapes}") from None
    return arrays, shape


def flat_values(arrays: Mapping[str, np.ndarray], shape: tuple[int, ...],
                keep_scalars: bool = True) -> dict[str, np.ndarray]:
    """Each swept array broadcast to ``shape`` and flattened (an array that has the shape
    already and is contiguous is passed as it is: no copy, no broadcast view); with
    ``keep_scalars`` a value given once (0-d) stays one value.

    >>> flat_values({"a": np.ones((2, 1)), "b": np.array(3.0)}, (2, 2))["a"].tolist()
    [1.0, 1.0, 1.0, 1.0]
    """
    return {path: a if keep_scalars and not a.ndim else
            np.ravel(a if a.shape == shape else np.broadcast_to(a, shape))
            for path, a in arrays.items()}


def shaped_views(arrays: Mapping[str, np.ndarray],
                 shape: tuple[int, ...]) -> Mapping[str, np.ndarray]:
    """Read-only views of the swept arrays in the broadcast ``shape`` (a result's
    ``parameters``: what ``np.broadcast_to`` gives, without its cost where the array has
    the shape already).

    >>> views = shaped_views({"a": np.arange(3.0)}, (2, 3))
    >>> views["a"].shape, views["a"].flags.writeable
    ((2, 3), False)
    """
    def view(a: np.ndarray) -> np.ndarray:
        if a.shape != shape:
            return np.broadcast_to(a, shape)
        same = a.view()
        same.flags.writeable = False
        return same

    return MappingProxyType({path: view(a) for path, a in arrays.items()})


def check_all(params: Sequence[Parameter], arrays: Mapping[str, np.ndarray]) -> None:
    """:func:`check_values` on each parameter's array, in order (the first out of range
    raises)."""
    for param in params:
        check_values(param, arrays[param.path])


def _bad_values(kind: str, array: np.ndarray) -> np.ndarray:
    with np.errstate(invalid="ignore"):
        return ~value_allowed(kind, array)


def value_allowed(kind: str, value):
    """Whether swept values of ``kind`` may go into a model: the one rule, for a float or an
    array, that :func:`check_values` enforces (and the sweep's numba kernels compile, in
    the per-kind functions below).

    >>> value_allowed("teeth", np.array([12, 0, 12.5])).tolist()
    [True, False, False]
    >>> bool(value_allowed("efficiency", 1.0)), bool(value_allowed("speed", np.inf))
    (True, False)
    """
    if kind == "teeth":
        return teeth_allowed(value)
    if kind == "efficiency":
        return efficiency_allowed(value)
    if kind == "ratio":
        return ratio_allowed(value)
    return port_value_allowed(value, port_limit(kind))


def port_limit(kind: str) -> float:
    """The largest speed, power or torque (SI, either way) a model file takes."""
    return _LIMITS.get(kind, math.inf)


def teeth_allowed(z):
    """Whole tooth numbers from 1 to ``MAX_TEETH`` (operators that floats, arrays and
    numba all take)."""
    return (z >= 1) & (z <= MAX_TEETH) & (z == np.floor(z))


def efficiency_allowed(e):
    """Efficiencies in (0, 1]."""
    return (e > 0) & (e <= 1)


def ratio_allowed(r):
    """Willis ratios that are numbers, non-zero and at most ``MAX_RATIO`` either way."""
    return (r == r) & (r != 0) & (abs(r) <= MAX_RATIO)


def port_value_allowed(x, limit: float):
    """Finite speeds, powers and torques at most ``limit`` either way."""
    return ((x - x) == 0) & (abs(x) <= limit)


def _rule(kind: str) -> str:
    limit = _LIMITS.get(kind)
    return {"teeth": f"teeth must be whole numbers >= 1 and <= {MAX_TEETH}",
            "efficiency": "efficiency must be in (0, 1]",
            "ratio": f"ratio must be non-zero, at most {MAX_RATIO:g} either way"}.get(
        kind, f"{kind} must be finite" + (f", at most {limit:g} (SI) either way"
                                          if limit else ""))


#: Largest port values (SI), as in model files.
_LIMITS = {"speed": MAX_SPEED, "power": MAX_POWER, "torque": MAX_TORQUE}


# --- --set PATH=START:STOP:N and grids ------------------------------------------------

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
    >>> rv = load_model("models/rv40e_wang2021.yaml")
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
    if not re.fullmatch(r"\s*[0-9]{1,12}\s*", parts[2]) or int(parts[2]) < 1:
        raise UsageError(f"--set {text!r}: N must be a whole number >= 1, got {parts[2]!r}")
    count = int(parts[2])
    if count > MAX_VARIANTS:
        raise UsageError(f"--set {text!r}: N must be at most {MAX_VARIANTS:,}")
    if count == 1 and start != stop:
        raise UsageError(f"--set {text!r}: N = 1 needs START = STOP")
    return np.linspace(start, stop, count)


def _number(text: str, item: str, kind: str, path: str) -> float:
    item = item.strip()
    try:
        value = float(item)
    except ValueError:
        pass
    else:
        if not math.isfinite(value):
            raise UsageError(f"--set {text!r}: {item!r} is not a finite number")
        return value
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
