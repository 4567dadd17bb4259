"""A train in one of its modes (docs/modes.md): the model with the mode's clutches and
brakes engaged (rigid, exactly as a ``fixed`` link) and every other shift element open
(no constraint, only its drag in its slip speed).

Freewheels are engaged or overrunning as ``freewheels`` says (default: overrunning); which
state is consistent is decided by :func:`powergraph.statics.modes.solve_mode`, which tries
them. Problems name the mode: ``modes.R: ...``.

Examples
--------
>>> from powergraph.model import load_model
>>> model = load_model("models/simpson_3speed.yaml")            # doctest: +SKIP
>>> first = resolve(model, "1")                                 # doctest: +SKIP
>>> first.mode, [b.id for b in first.bodies][:2]                # doctest: +SKIP
('1', ['0/c2', 'in/r1'])
"""
from __future__ import annotations

import dataclasses
from typing import Iterable, Mapping

from powergraph.errors import ModelError
from powergraph.model.spec import Model


def mode_path(mode: str) -> str:
    """The place of a mode in the file, for messages (``modes.R``)."""
    return f"modes.{mode}"


def engaged_in(model: Model, mode: str) -> tuple[str, ...]:
    """The clutches and brakes the mode engages (UsageError-free: ModelError when unknown)."""
    if mode not in model.modes:
        known = ", ".join(model.modes) or "none"
        raise ModelError(f"unknown mode {mode!r} (the model's modes: {known})", "modes")
    return model.modes[mode]


def resolve(model: Model, mode: str | None,
            freewheels: Mapping[str, bool] | None = None,
            engaged: Iterable[str] | None = None) -> Model:
    """The model in ``mode`` (a key of ``model.modes``), or with the elements ``engaged``.

    Parameters
    ----------
    model : Model
        A model with shift elements (any model: one without is returned unchanged).
    mode : str or None
        The mode; None with ``engaged`` to engage a set of elements by name.
    freewheels : mapping, optional
        ``{freewheel name: engaged?}``; freewheels not named overrun.
    engaged : iterable of str, optional
        The engaged clutch/brake names when ``mode`` is None.

    Returns
    -------
    Model
        A new model whose ``links`` hold each shift element as ``fixed`` (engaged) or
        ``bearing`` (open), with its bodies rebuilt, ``mode`` set and the mode in its name
        (``Simpson 3-speed [R]``).

    Raises
    ------
    ModelError
        ``modes.NAME: engages ...: ...`` when the mode joins what cannot be joined (a
        port held by a brake, a mesh inside one rigid body...).
    """
    from powergraph.model.graph import bodies_of, check_topology
    from powergraph.model.shift import as_link

    names = set(engaged_in(model, mode) if mode is not None else (engaged or ()))
    names |= {n for n, on in (freewheels or {}).items() if on}
    links = list(model.links)
    for element in model.shift_elements:
        links[element.index] = as_link(element, element.name in names)
    bodies, body_of = bodies_of(model.components, tuple(links))
    derived = dataclasses.replace(model, links=tuple(links), bodies=bodies,
                                  body_of=body_of, mode=mode,
                                  name=model.name if mode is None else f"{model.name} [{mode}]")
    try:
        check_topology(derived)
    except ModelError as error:
        where = mode_path(mode) if mode is not None else error.path
        raise ModelError(f"engages {_listing(names)}: {error.message}", where) from None
    return derived


def _listing(names: Iterable[str]) -> str:
    names = sorted(names)
    return ", ".join(names) if names else "nothing"
