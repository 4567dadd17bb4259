"""The model values a tolerance PATH addresses.

The PATHs are those of ``powergraph sweep --set`` (:mod:`powergraph.model.paths`,
whose :func:`~powergraph.model.paths.parse_path` resolves the power-flow values),
extended into the analysis blocks of a mesh:

====================================================  =====================================
``links.<i>.efficiency``, ``links.*.efficiency``       basic efficiency, (0, 1]
``links.<i>.backlash_arcmin``                          play of the mesh's first gear, ≥ 0
``links.<i>.backlash.measured_M.<gear>``               over-pin distance M of one gear, mm
                                                       (one value per unit: it replaces
                                                       the list of measurements)
``links.<i>.backlash.runout.<gear>``                   radial runout F_r, mm, ≥ 0
``links.<i>.backlash.bearing_clearance.<k>``           radial clearance u_r of bearing k,
                                                       mm, ≥ 0
``links.<i>.cycloid.profile_error``                    profile error d of the disc, mm, ≥ 0
====================================================  =====================================

``links[1].backlash.runout.R2`` (the form of the model's error messages) works too. Each
value must exist in the model: a tolerance varies a nominal value, it does not add one.
Tooth numbers, Willis ratios, port values and geometry dimensions are not toleranced here
(none of them is a tolerance of a part that changes the outputs computed).

Examples
--------
>>> from powergraph.model import loads_model
>>> m = loads_model('''
... name: pair
... components: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 60}}
... links: [{type: mesh, between: [1, 2], backlash_arcmin: 6.0}]
... ports: [{component: 1, role: input}, {component: 2, role: output}]
... ''')
>>> resolve_path(m, "links[0].backlash_arcmin")
Target(path='links[0].backlash_arcmin', kind='backlash_arcmin', links=(0,), key=None)
"""
from __future__ import annotations

import re

from powergraph.errors import ModelError, PowerGraphError
from powergraph.model.paths import parse_path
from powergraph.model.spec import Model
from powergraph.records import record

#: kind -> (domain low, domain high, low bound excluded, is a length)
DOMAINS = {
    "efficiency": (0.0, 1.0, True, False),
    "backlash_arcmin": (0.0, None, False, False),
    "measured_M": (0.0, None, True, True),
    "runout": (0.0, None, False, True),
    "bearing_clearance": (0.0, None, False, True),
    "profile_error": (0.0, None, False, True),
}
BLOCK_FIELDS = {"backlash": ("measured_M", "runout", "bearing_clearance"),
                "cycloid": ("profile_error",)}
UNITS = {"efficiency": "", "backlash_arcmin": "arcmin", "measured_M": "mm", "runout": "mm",
         "bearing_clearance": "mm", "profile_error": "mm"}


@record
class Target:
    """One toleranced model value.

    Attributes
    ----------
    path : str
        The PATH as written.
    kind : str
        ``efficiency``, ``backlash_arcmin``, ``measured_M``, ``runout``,
        ``bearing_clearance`` or ``profile_error``.
    links : tuple of int
        The link(s) it belongs to (several for ``links.*.efficiency``).
    key : str or int or None
        The gear id (``measured_M``, ``runout``) or bearing index (``bearing_clearance``).
    """

    path: str
    kind: str
    links: tuple[int, ...]
    key: str | int | None = None

    @property
    def values(self) -> tuple[tuple, ...]:
        """The model values it sets (two PATHs may not share one)."""
        return tuple((self.kind, link, self.key) for link in self.links)


def place_of(path: str) -> str:
    """The place of a tolerance entry in messages: ``tolerances['PATH']``."""
    return f"tolerances[{path!r}]"


def resolve_path(model: Model, path: str) -> Target:
    """The :class:`Target` a tolerance PATH addresses in ``model``.

    Raises
    ------
    ModelError
        Naming ``tolerances['PATH']``: a malformed PATH, something the model does not
        have, or a value that is not toleranced.
    """
    place = place_of(path)
    if not isinstance(path, str) or not path.strip():
        raise ModelError("a PATH must be non-empty text", place)
    parts = re.sub(r"\[([^\]]*)\]", r".\1", path.strip()).split(".")
    if parts[0] == "components" and "geometry" in parts:
        raise ModelError("component geometry is not toleranced here: it changes none of "
                         "the outputs (lost motion, fluctuation, efficiency); a cycloid "
                         "disc's profile is links.<i>.cycloid.profile_error", place)
    if parts[0] != "links":
        raise ModelError("only links.<i>.efficiency, links.<i>.backlash_arcmin, "
                         "links.<i>.backlash.… and links.<i>.cycloid.profile_error are "
                         "toleranced (lost motion, fluctuation, efficiency)", place)
    if len(parts) == 3 and parts[2] == "efficiency":
        return _efficiency(model, path, place)
    if len(parts) < 3:
        raise ModelError("expected links.<i>.<value>", place)
    link = model.links[_link_index(model, parts[1], place)]
    if link.type != "mesh":
        raise ModelError(f"links[{link.index}] is a {link.type} link: it has no "
                         f"{parts[2]}", place)
    if parts[2] == "backlash_arcmin" and len(parts) == 3:
        if "backlash_arcmin" not in link.blocks:
            raise ModelError(f"links[{link.index}] has no backlash_arcmin (a tolerance varies "
                             "a nominal value the model gives)", place)
        return Target(path, "backlash_arcmin", (link.index,))
    if parts[2] in BLOCK_FIELDS:
        return _block_field(link, parts[2], parts[3:], path, place)
    raise ModelError(f"{'.'.join(parts[2:])!r} is not toleranced (a mesh's toleranced "
                     "values: efficiency, backlash_arcmin, backlash.measured_M.<gear>, "
                     "backlash.runout.<gear>, backlash.bearing_clearance.<k>, "
                     "cycloid.profile_error)", place)


def _link_index(model: Model, text: str, place: str) -> int:
    if not re.fullmatch(r"\d+", text):
        raise ModelError(f"a link index must be a whole number, got {text!r}", place)
    index = int(text)
    if index >= len(model.links):
        raise ModelError(f"no links[{index}] (the model has {len(model.links)} links)", place)
    return index


def _efficiency(model: Model, path: str, place: str) -> Target:
    try:
        parameter = parse_path(model, path)
    except PowerGraphError as exc:
        raise ModelError(exc.message, place) from None
    return Target(path, "efficiency", tuple(parameter.targets))


def _block_field(link, block_name: str, rest: list[str], path: str, place: str) -> Target:
    block = link.blocks.get(block_name)
    if block is None:
        raise ModelError(f"links[{link.index}] has no {block_name}: block", place)
    fields = BLOCK_FIELDS[block_name]
    if not rest or rest[0] not in fields:
        raise ModelError(f"{block_name}.{'.'.join(rest) or '(nothing)'} is not toleranced "
                         f"(allowed: {', '.join(f'{block_name}.{f}' for f in fields)})",
                         place)
    field, keys = rest[0], rest[1:]
    if field == "profile_error":
        if keys:
            raise ModelError("expected links.<i>.cycloid.profile_error", place)
        return Target(path, field, (link.index,))
    if len(keys) != 1:
        what = "<k>" if field == "bearing_clearance" else "<gear>"
        raise ModelError(f"expected links.<i>.backlash.{field}.{what}", place)
    if field == "bearing_clearance":
        count = len(block.bearing_clearance)
        if not re.fullmatch(r"\d+", keys[0]) or int(keys[0]) >= count:
            raise ModelError(f"no bearing_clearance[{keys[0]}] (links[{link.index}] gives "
                             f"{count})", place)
        return Target(path, field, (link.index,), int(keys[0]))
    if keys[0] not in (block.internal, block.external):
        raise ModelError(f"{keys[0]!r} is not a gear of links[{link.index}] (the gears are "
                         f"{block.internal!r} and {block.external!r})", place)
    return Target(path, field, (link.index,), keys[0])
