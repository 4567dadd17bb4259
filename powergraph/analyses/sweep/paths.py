"""Sweep parameters: the model values a PATH addresses, and checks on the values swept.

A PATH names one number of the model file (SPEC §1):

=============================  =========================================================
``components.<id>.teeth``      tooth number (integer >= 1); changes the Willis ratio of
                               every mesh of that gear that gives no ``ratio``, with the
                               sign from the model's ``internal`` flags
``links.<i>.efficiency``       basic efficiency of mesh (or coupling) ``links[i]``, (0, 1]
``links.*.efficiency``         every mesh at once (like ``solve --mesh-efficiency``)
``links.<i>.ratio``            Willis quotient ``(w_a - w_c)/(w_b - w_c)`` of mesh ``i``
``ports.<i>.speed``            speed of ``ports[i]``, rad/s
``ports.<i>.power``            power of ``ports[i]``, W
``ports.<i>.torque``           torque of ``ports[i]``, N·m
=============================  =========================================================

``links[1].efficiency`` (the form of the model's error messages) is accepted too.
"""
from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

from powergraph.errors import ModelError, UsageError
from powergraph.model.spec import Model

LINK_FIELDS = ("efficiency", "ratio")
PORT_FIELDS = ("speed", "power", "torque")


@dataclass(frozen=True)
class Parameter:
    """One swept model value.

    Attributes
    ----------
    path : str
        The PATH as the user wrote it (the CSV column name).
    kind : str
        ``teeth``, ``efficiency``, ``ratio``, ``speed``, ``power`` or ``torque``.
    targets : tuple
        Component id (teeth), link indices (efficiency, ratio) or port index (ports).
    """

    path: str
    kind: str
    targets: tuple

    @property
    def is_port(self) -> bool:
        return self.kind in PORT_FIELDS


def parse_path(model: Model, path: str) -> Parameter:
    """The :class:`Parameter` a PATH addresses in ``model``.

    Raises
    ------
    UsageError
        The PATH is not of a form listed above.
    ModelError
        It names something the model does not have, or a value that cannot be swept.

    Examples
    --------
    >>> from powergraph.model import load_model
    >>> rv = load_model("models/rv40e.yaml")                         # doctest: +SKIP
    >>> parse_path(rv, "links.1.efficiency")                         # doctest: +SKIP
    Parameter(path='links.1.efficiency', kind='efficiency', targets=(1,))
    """
    if not isinstance(path, str) or not path:
        raise UsageError(f"a sweep PATH must be non-empty text, got {path!r}")
    text = re.sub(r"\[([^\]]*)\]", r".\1", path.strip())
    head, _, rest = text.partition(".")
    if head == "components":
        return _component_path(model, path, rest)
    if head == "links":
        return _link_path(model, path, rest)
    if head == "ports":
        return _port_path(model, path, rest)
    raise UsageError(f"sweep PATH {path!r}: must start with components., links. or ports. "
                     "(e.g. components.5.teeth, links.1.efficiency, ports.0.speed)")


def _component_path(model: Model, path: str, rest: str) -> Parameter:
    cid, _, field = rest.rpartition(".")
    if not cid:
        raise UsageError(f"sweep PATH {path!r}: expected components.<id>.teeth")
    if cid not in model.components:
        raise ModelError(f"unknown component {cid!r}", path)
    if field != "teeth":
        raise ModelError(f"{field!r} cannot be swept (a component's sweepable value is "
                         "teeth)", path)
    if model.components[cid].teeth is None:
        raise ModelError(f"component {cid!r} has no teeth in the model", path)
    return Parameter(path, "teeth", (cid,))


def _index(text: str, size: int, what: str, path: str) -> int:
    if not re.fullmatch(r"\d+", text):
        raise UsageError(f"sweep PATH {path!r}: {what} index must be a whole number, got "
                         f"{text!r}")
    index = int(text)
    if index >= size:
        raise ModelError(f"the model has {size} {what}s (0…{size - 1}), no {what} {index}",
                         path)
    return index


def _link_path(model: Model, path: str, rest: str) -> Parameter:
    where, _, field = rest.partition(".")
    if field not in LINK_FIELDS:
        raise ModelError(f"{field or '(nothing)'!r} cannot be swept (a link's sweepable "
                         f"values are {', '.join(LINK_FIELDS)})", path)
    if where == "*":
        if field != "efficiency":
            raise UsageError(f"sweep PATH {path!r}: only links.*.efficiency addresses every "
                             "mesh")
        meshes = tuple(link.index for link in model.meshes)
        if not meshes:
            raise ModelError("the model has no meshes", path)
        return Parameter(path, "efficiency", meshes)
    link = model.links[_index(where, len(model.links), "link", path)]
    if field == "efficiency" and link.type not in ("mesh", "coupling"):
        raise ModelError(f"links[{link.index}] is a {link.type} link: it has no efficiency",
                         path)
    if field == "ratio" and link.type != "mesh":
        raise ModelError(f"links[{link.index}] is a {link.type} link: only a mesh has a "
                         "ratio", path)
    return Parameter(path, field, (link.index,))


def _port_path(model: Model, path: str, rest: str) -> Parameter:
    where, _, field = rest.partition(".")
    if field not in PORT_FIELDS:
        raise ModelError(f"{field or '(nothing)'!r} cannot be swept (a port's sweepable "
                         f"values are {', '.join(PORT_FIELDS)})", path)
    port = model.ports[_index(where, len(model.ports), "port", path)]
    other = {"power": "torque", "torque": "power"}.get(field)
    if other and getattr(port, other) is not None:
        raise ModelError(f"ports[{port.index}] gives {other}: a port takes at most one of "
                         f"power and torque (sweep ports.{port.index}.{other})", path)
    return Parameter(path, field, (port.index,))


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
        Naming the PATH: teeth that are not whole numbers >= 1, efficiencies outside
        (0, 1], a zero or non-finite ratio, a non-finite speed, power or torque.
    """
    kind = param.kind
    low = np.minimum.reduce(array, axis=None)
    if kind == "teeth" and array.dtype.kind in "iu":   # integers: only the lower bound
        high = low
    else:
        high = np.maximum.reduce(array, axis=None)
    if kind == "teeth":
        ok = low >= 1 and np.isfinite(high) and (
            array.dtype.kind in "iu" or np.array_equal(np.floor(array), array))
    elif kind == "efficiency":
        ok = low > 0 and high <= 1
    else:
        ok = np.isfinite(low) and np.isfinite(high) and (
            kind != "ratio" or (low > 0 or high < 0 or np.all(array != 0)))
    if not ok:
        bad = _bad_values(kind, np.asarray(array, dtype=float))
        first = np.asarray(array)[bad].flat[0]
        count = int(np.count_nonzero(bad))
        raise ModelError(f"{_rule(kind)}; got {float(first):g}"
                         + (f" ({count} of {array.size} values are out of range)"
                            if count > 1 else ""), param.path)
    return array


def _bad_values(kind: str, array: np.ndarray) -> np.ndarray:
    finite = np.isfinite(array)
    if kind == "teeth":
        return ~finite | (array < 1) | (array != np.round(array))
    if kind == "efficiency":
        return ~finite | (array <= 0) | (array > 1)
    if kind == "ratio":
        return ~finite | (array == 0)
    return ~finite


def _rule(kind: str) -> str:
    return {"teeth": "teeth must be whole numbers >= 1",
            "efficiency": "efficiency must be in (0, 1]",
            "ratio": "ratio must be a non-zero finite number"}.get(kind, f"{kind} must be "
                                                                         "finite")
