"""A sweep's variant as a model: the swept values written into a copy of the model, for
the variants solved one by one (a mode whose freewheels are decided at each load, a train
with machines on buses, a variant the vectorised iteration hands over).

Examples
--------
>>> from powergraph.model import load_model
>>> from powergraph.analyses.sweep.paths import parse_paths
>>> m = load_model("models/planetary_2kh_sun_to_carrier.yaml")
>>> params = parse_paths(m, ["components.ring.teeth", "ports.0.power"])
>>> v = with_values(m, params, {"components.ring.teeth": np.array([48.0, 96.0]),
...                             "ports.0.power": np.float64(500.0)}, 1)
>>> v.components["ring"].teeth, v.ports[0].power
(96.0, 500.0)
"""
from __future__ import annotations

import dataclasses
from types import MappingProxyType
from typing import Mapping

import numpy as np

from powergraph.model.paths import Parameter
from powergraph.model.spec import Model


def with_values(model: Model, parameters: tuple[Parameter, ...],
                flat: Mapping[str, np.ndarray], index: int) -> Model:
    """``model`` with variant ``index`` of the flattened values ``flat`` (``{PATH: array
    over the variants, or a scalar}``) written in: a tooth number into its component
    (every mesh of that gear that gives no ``ratio`` follows it), an efficiency or ratio
    into its links, a port's speed, or its load (replacing a load of the other kind)."""
    for param in parameters:
        values = np.asarray(flat[param.path])
        model = with_value(model, param, float(values if values.ndim == 0 else values[index]))
    return model


def with_value(model: Model, param: Parameter, value: float) -> Model:
    """``model`` with the value at one PATH set to ``value`` (SI)."""
    if param.kind == "teeth":
        components = dict(model.components)
        components[param.targets[0]] = dataclasses.replace(components[param.targets[0]],
                                                           teeth=value)
        return dataclasses.replace(model, components=MappingProxyType(components))
    if param.kind in ("efficiency", "ratio"):
        for link in param.targets:
            model = model.with_link(link, **{param.kind: value})
        return model
    load = {} if param.kind == "speed" else {"power": None, "torque": None}
    return model.with_port(param.targets[0], **{**load, param.kind: value})
