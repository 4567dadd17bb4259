"""The model's top-level ``tolerances:`` block: PATH -> distribution, validated.

Called by the model layer when a model file has ``tolerances:`` (so ``powergraph check``
catches every mistake), and stored on the model as a :class:`Tolerances`::

    tolerances:
      links.0.backlash_arcmin: {distribution: uniform, min: 0.5, max: 1.5}
      links.1.backlash.runout.R2: {nominal: 0.01, tolerance: 0.005}
      links.1.cycloid.profile_error: {nominal: 0.005, grade: IT6, size: 124.8}
      links.1.efficiency: {distribution: normal, mean: 0.995, sd: 0.001, high: 1}

Examples
--------
>>> from powergraph.model import loads_model
>>> m = loads_model('''
... name: pair
... components: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 60}}
... links: [{type: mesh, between: [1, 2], backlash_arcmin: 6.0}]
... ports: [{component: 1, role: input}, {component: 2, role: output}]
... tolerances:
...   links.0.backlash_arcmin: {distribution: uniform, min: 5, max: 7}
... ''')
>>> [(t.target.kind, t.distribution.low) for t in m.tolerances.entries]
[('backlash_arcmin', 5.0)]
"""
from __future__ import annotations

from typing import Any

from powergraph.errors import ModelError
from powergraph.model.distributions import Distribution, parse_distribution
from powergraph.model.tolerance_paths import DOMAINS, Target, place_of, resolve_path
from powergraph.records import record


@record
class Tolerance:
    """One toleranced value: where it is and how it is distributed."""

    target: Target
    distribution: Distribution

    @property
    def path(self) -> str:
        return self.target.path


@record
class Tolerances:
    """Every toleranced value of a model, in file order."""

    entries: tuple[Tolerance, ...]

    @property
    def paths(self) -> tuple[str, ...]:
        return tuple(t.path for t in self.entries)

    def __len__(self) -> int:
        return len(self.entries)

    def to_dict(self) -> dict:
        return {t.path: t.distribution.to_dict() for t in self.entries}


def validate_tolerances(raw: Any, model) -> Tolerances:
    """Validate a ``tolerances:`` mapping against a (validated) model.

    Raises
    ------
    ModelError
        Naming ``tolerances['PATH']`` (or ``tolerances``): a PATH the model does not have,
        a malformed distribution, a support outside the value's domain, two PATHs that set
        the same value.
    """
    if not isinstance(raw, dict):
        raise ModelError(f"must be a mapping {{PATH: distribution}}, got "
                         f"{type(raw).__name__}", "tolerances")
    if not raw:
        raise ModelError("empty (leave the key out when nothing is toleranced)", "tolerances")
    entries, seen = [], {}
    for path, spec in raw.items():
        if not isinstance(path, str):
            raise ModelError(f"a PATH must be text, got {path!r}", "tolerances")
        target = resolve_path(model, path)
        for value in target.values:
            if value in seen:
                raise ModelError(f"sets the same model value as {seen[value]!r}",
                                 place_of(path))
            seen[value] = path
        low, high, open_low, length = DOMAINS[target.kind]
        dist = parse_distribution(spec, place_of(path), (low, high), length=length,
                                  open_low=open_low)
        entries.append(Tolerance(target, dist))
    return Tolerances(tuple(entries))
