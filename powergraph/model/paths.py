"""The model values a PATH addresses (``powergraph sweep --set``, tolerances, synthesis).

A PATH names one number of the model file (docs/format.md):

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

from powergraph.errors import ModelError, UsageError
from powergraph.model.spec import Model
from powergraph.records import record

LINK_FIELDS = ("efficiency", "ratio")
PORT_FIELDS = ("speed", "power", "torque")


@record
class Parameter:
    """One swept model value: the ``path`` as the user wrote it (the CSV column name), its
    ``kind`` (``teeth``, ``efficiency``, ``ratio``, ``speed``, ``power`` or ``torque``) and
    its ``targets``: a component id (teeth), link indices (efficiency, ratio) or a port
    index (ports)."""

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
    >>> rv = load_model("models/rv40e_wang2021.yaml")                         # doctest: +SKIP
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


def _where_field(rest: str, fields: tuple[str, ...], what: str, path: str) -> tuple[str, str]:
    """``<where>.<field>`` of a link or port PATH, the field one that can be swept."""
    where, _, field = rest.partition(".")
    if field not in fields:
        raise ModelError(f"{field or '(nothing)'!r} cannot be swept (a {what}'s sweepable "
                         f"values are {', '.join(fields)})", path)
    return where, field


def _link_path(model: Model, path: str, rest: str) -> Parameter:
    where, field = _where_field(rest, LINK_FIELDS, "link", path)
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
    where, field = _where_field(rest, PORT_FIELDS, "port", path)
    port = model.ports[_index(where, len(model.ports), "port", path)]
    other = {"power": "torque", "torque": "power"}.get(field)
    if other and getattr(port, other) is not None:
        raise ModelError(f"ports[{port.index}] gives {other}: a port takes at most one of "
                         f"power and torque (sweep ports.{port.index}.{other})", path)
    return Parameter(path, field, (port.index,))
