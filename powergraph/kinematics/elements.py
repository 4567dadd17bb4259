"""The train's kinematic elements: meshes (Willis rows) and couplings (equal speeds).

A coupling is treated as a pair of ratio +1 whose carrier is the frame: its row
``w_a - w_b = 0`` is then Willis' row, and an optional coupling efficiency acts like a
mesh's (the loss torque reacts on the frame).
"""
from __future__ import annotations

from operator import attrgetter
from typing import Mapping, NamedTuple, TypeVar

import numpy as np

from powergraph.model.spec import Link, Model

#: A number, a numpy array or a sympy expression: the stencil is the same for all three.
Value = TypeVar("Value")


class Element(NamedTuple):
    """One mesh or coupling, resolved to bodies.

    ``ratio`` is Willis' quotient ``(w_a - w_c)/(w_b - w_c)``; ``a``, ``b``, ``carrier``
    are component ids and ``body_a``, ``body_b``, ``body_c`` their bodies.
    """

    link: int
    kind: str
    a: str
    b: str
    carrier: str
    body_a: str
    body_b: str
    body_c: str
    ratio: float
    efficiency: float

    @property
    def bodies(self) -> tuple[str, str, str]:
        return self.body_a, self.body_b, self.body_c


def element_stencil(ratio: Value, factor: Value | float = 1.0) -> tuple[float, Value, Value]:
    """The one place where an element's physics is written: its coefficients on gear a,
    gear b and the carrier.

    With ``factor = 1`` they are the element's **kinematic row** (Willis' relation
    ``(w_a - w_c) - i (w_b - w_c) = 0`` written as ``1·w_a - i·w_b + (i - 1)·w_c = 0``).
    With the element's factor ``f`` (``η`` when gear a drives in the carrier's frame,
    ``1/η`` when gear b drives, 1 when ideal) they are its **static column**: the torques it
    applies to gear a, gear b and the carrier per unit of its force ``λ``. The static column
    is the kinematic row with ``i`` replaced by ``i·f`` (the principle of virtual power: an
    ideal element's torques do no work in any frame). ``ratio`` and ``factor`` may be
    floats, numpy arrays (one value per variant) or sympy expressions.

    Parameters
    ----------
    ratio : float, array or sympy expression
        Willis' quotient ``i = (w_a - w_c)/(w_b - w_c)``.
    factor : float, array or sympy expression, optional
        The element's efficiency factor ``f`` (default 1: the kinematic row).

    Returns
    -------
    (coefficient of gear a, of gear b, of the carrier)

    Examples
    --------
    >>> element_stencil(-2.5)
    (1.0, 2.5, -3.5)
    >>> element_stencil(-2.5, 0.98)
    (1.0, 2.45, -3.45)
    """
    scaled = ratio * factor
    return 1.0, -scaled, scaled - 1.0


def gear_torque(ratio: Value, force: Value, factor: Value | float = 1.0,
                on_gear_a: bool = True) -> Value:
    """The torque an element applies to its gear a (or gear b): that gear's entry of the
    static column (:func:`element_stencil`) times the element's force ``λ``. Floats or
    arrays of operating points.

    >>> gear_torque(-2.5, 4.0), gear_torque(-2.5, 4.0, 0.98, on_gear_a=False)
    (4.0, 9.8)
    """
    on_a, on_b, _ = element_stencil(ratio, factor)
    return (on_a if on_gear_a else on_b) * force


def willis_ratio(link: Link, model: Model) -> float:
    """Willis' quotient ``(w_a - w_c)/(w_b - w_c)`` of a mesh (docs/format.md).

    ``-z_b/z_a`` for an external pair, ``+z_b/z_a`` when either gear is internal, or the
    link's ``ratio`` when given.

    Examples
    --------
    >>> from powergraph.model import model_from_dict
    >>> m = model_from_dict({"name": "p", "components": {0: {"role": "frame"},
    ...     1: {"teeth": 20}, 2: {"teeth": 50}},
    ...     "links": [{"type": "mesh", "between": [1, 2]}],
    ...     "ports": [{"component": 1, "role": "input"}, {"component": 2, "role": "output"}]})
    >>> willis_ratio(m.links[0], m)
    -2.5
    """
    if link.ratio is not None:
        return link.ratio
    a, b = (model.components[x] for x in link.between)
    sign = 1.0 if (a.internal or b.internal) else -1.0
    return sign * b.teeth / a.teeth


def elements_of(model: Model) -> tuple[Element, ...]:
    """Meshes and couplings of ``model`` in file order (computed once per model)."""
    cached = model.derived.get("kinematics.elements")
    if cached is None:
        cached = model.derived["kinematics.elements"] = _elements_of(model)
    return cached


def _elements_of(model: Model) -> tuple[Element, ...]:
    out = []
    for link in model.links:
        if link.type == "mesh":
            carrier, ratio = link.carrier, willis_ratio(link, model)
        elif link.type == "coupling":
            carrier, ratio = model.frame, 1.0
        else:
            continue
        a, b = link.between
        out.append(Element(link=link.index, kind=link.type, a=a, b=b, carrier=carrier,
                           body_a=model.body_of[a], body_b=model.body_of[b],
                           body_c=model.body_of[carrier], ratio=ratio,
                           efficiency=link.efficiency))
    return tuple(out)


#: An element's three bodies (gear a, gear b, carrier) as a tuple, fast.
ELEMENT_BODIES = attrgetter("body_a", "body_b", "body_c")


def body_columns(elements: tuple[Element, ...], index: Mapping[str, object]) -> np.ndarray:
    """``index[body]`` of each element's gear a, gear b and carrier: an ``(n, 3)`` array
    (indices, or speeds when ``index`` maps bodies to speeds).

    >>> e = Element(0, "mesh", "1", "2", "0", "1", "2", "0", -2.0, 0.9)
    >>> body_columns((e,), {"0": 0, "1": 1, "2": 2}).tolist()
    [[1, 2, 0]]
    """
    flat = [index[b] for triple in map(ELEMENT_BODIES, elements) for b in triple]
    return np.array(flat).reshape(len(elements), 3)
