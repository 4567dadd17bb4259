"""Model layer: YAML reading, validation, the immutable model and its graph (docs/format.md)."""
from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import Any

from powergraph.model.graph import to_networkx
from powergraph.model.input_files import is_rexs_path
from powergraph.model.spec import Body, Component, Link, Model, Port
from powergraph.model.validate import model_from_dict
from powergraph.model.yaml_loader import load_yaml_file, load_yaml_text

__all__ = ["Body", "Component", "Link", "Model", "Port", "load_model", "load_model_data",
           "loads_model", "model_from_dict", "to_networkx"]


def load_model(path: str | Path) -> Model:
    """Read and validate a model file.

    Parameters
    ----------
    path : str or Path
        A YAML model file (format: docs/format.md), or a REXS file (``.rexs`` XML,
        ``.rexsj`` JSON) read by :func:`powergraph.model.rexs_reader.read_rexs`
        (docs/exchange.md).

    Returns
    -------
    Model

    Raises
    ------
    ModelError
        With the place in the file and the problem.

    Examples
    --------
    >>> model = load_model("models/rv40e_wang2021.yaml")      # doctest: +SKIP
    >>> model.name                                   # doctest: +SKIP
    'RV-40E'
    """
    if not is_rexs_path(path):
        return model_from_dict(load_yaml_file(path), source=str(path))
    from powergraph.model.rexs_reader import read_rexs, rexs_caveats

    imported = read_rexs(path)
    model = model_from_dict(imported.data, source=str(path))
    return dataclasses.replace(model, warnings=model.warnings + rexs_caveats(imported))


def load_model_data(path: str | Path) -> Any:
    """The plain data of a model file (as YAML gives it), before validation: a REXS file
    (``.rexs``, ``.rexsj``) through :func:`powergraph.model.rexs_reader.read_rexs`."""
    if is_rexs_path(path):
        from powergraph.model.rexs_reader import read_rexs

        return read_rexs(path).data
    return load_yaml_file(path)


def loads_model(text: str, source: str = "<model>") -> Model:
    """Validate a model given as YAML text (see :func:`load_model`)."""
    return model_from_dict(load_yaml_text(text, source), source=source)
