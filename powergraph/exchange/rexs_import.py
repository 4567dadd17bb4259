"""A REXS file turned into a model file and duty-cycle points (``powergraph import``).

The model is what :func:`powergraph.model.rexs_reader.read_rexs` reads, validated (so a
file that gives no valid train fails here, not later) and written as YAML; the load
spectrum's load cases as a points CSV that ``powergraph cycle`` reads (docs/hybrid.md):
``duration [s]`` (each case's fraction of one hour), then ``PORT.speed [rpm]`` and
``PORT.torque [N*m]`` columns, the ports named by their component ids.

Examples
--------
>>> result = import_rexs("tests/exchange/data/two_stage_helical.rexs")   # doctest: +SKIP
>>> print(points_csv(result.points).splitlines()[0])                     # doctest: +SKIP
duration [s],10.speed [rpm],10.torque [N*m]
"""
from __future__ import annotations

from pathlib import Path

import yaml

from powergraph.errors import ModelError
from powergraph.model import model_from_dict
from powergraph.model.rexs_reader import RexsImport, read_rexs, rexs_caveats


def import_rexs(path: str | Path, mesh_efficiency: float | None = None) -> RexsImport:
    """Read and validate a REXS file: the :class:`RexsImport` of a valid model."""
    result = read_rexs(path, mesh_efficiency)
    model_from_dict(result.data, source=str(path))
    return result


def model_yaml(result: RexsImport, source: str) -> str:
    """The imported model as the text of a YAML model file, with a header naming the
    source and what was not mapped."""
    header = [f"# Imported from {Path(source).name} by powergraph import (docs/exchange.md)."]
    header += [f"# Warning: {c}" for c in ideal_meshes(result)]
    if result.unmapped:
        header.append("# Not mapped:")
        header += [f"#   {line}" for line in result.unmapped]
    body = yaml.safe_dump(result.data, sort_keys=False, allow_unicode=True, width=100)
    return "\n".join(header) + "\n" + body


def ideal_meshes(result: RexsImport) -> tuple:
    """The warning that the imported meshes are ideal (none when they have efficiencies)."""
    return tuple(c for c in rexs_caveats(result) if c.code == "rexs-ideal-meshes")


def points_csv(points: tuple[dict[str, float], ...]) -> str:
    """The load cases as duty-cycle points (one header line, one row per load case).

    >>> print(points_csv(({"duration [s]": 900.0, "1.speed [rpm]": 1500.0},)), end="")
    duration [s],1.speed [rpm]
    900.0,1500.0
    """
    if not points:
        raise ModelError("the file has no load spectrum: no points to write", "--points")
    columns = list(dict.fromkeys(key for row in points for key in row))
    lines = [",".join(columns)]
    for number, row in enumerate(points, 1):
        missing = [c for c in columns if c not in row]
        if missing:
            raise ModelError(f"load case {number} gives no {missing[0]} where another case "
                             "does", "--points")
        lines.append(",".join(repr(float(row[c])) for c in columns))
    return "\n".join(lines) + "\n"
