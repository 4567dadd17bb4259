"""The model format's one description (a JSON Schema): published, documented, enforced.

The schema is checked with the independent ``jsonschema`` package: it is a valid draft
2020-12 schema, every library model satisfies it, and format mistakes that the program
refuses are refused by ``jsonschema`` too (so editors and the program agree).
"""
from __future__ import annotations

import copy
import io
import json
import math
import re
from contextlib import redirect_stdout
from pathlib import Path

import jsonschema
import pytest
import yaml

from powergraph.cli.main import main
from powergraph.errors import ModelError
from powergraph.model import load_model, loads_model, model_from_dict
from powergraph.model.schema import MODEL_SCHEMA

ROOT = Path(__file__).resolve().parents[2]
MODELS = sorted((ROOT / "models").glob("*.yaml"))
VALIDATOR = jsonschema.Draft202012Validator(MODEL_SCHEMA)


def as_json(data):
    """The document as an editor's language server sees it (keys are strings)."""
    return json.loads(json.dumps(data))


def schema_nodes(node, path="#"):
    """Every (path, property name, property schema) of the schema."""
    if isinstance(node, dict):
        for name, sub in node.get("properties", {}).items():
            yield path, name, sub
        for key, value in node.items():
            yield from schema_nodes(value, f"{path}/{key}")
    elif isinstance(node, list):
        for index, value in enumerate(node):
            yield from schema_nodes(value, f"{path}/{index}")


def test_committed_schema_file_is_the_command_output() -> None:
    out = io.StringIO()
    with redirect_stdout(out):
        assert main(["schema"]) == 0
    assert out.getvalue() == (ROOT / "docs" / "powergraph.schema.json").read_text()
    assert json.loads(out.getvalue())["$schema"] == \
        "https://json-schema.org/draft/2020-12/schema"


def test_schema_is_valid_draft_2020_12() -> None:
    jsonschema.Draft202012Validator.check_schema(MODEL_SCHEMA)


def test_every_field_has_a_title_and_description_and_is_documented() -> None:
    doc = (ROOT / "docs" / "format.md").read_text()
    names = set()
    for where, name, sub in schema_nodes(MODEL_SCHEMA):
        names.add(name)
        if "$ref" in sub and "title" not in sub:
            continue  # described at its definition
        assert sub.get("title") and sub.get("description"), f"{where}/properties/{name}"
    for name in names:
        assert f"`{name}`" in doc, f"docs/format.md does not describe `{name}`"


def test_defaults_in_the_schema_are_the_defaults_the_model_applies() -> None:
    model = loads_model("""
name: t
components: {0: {role: frame}, 1: {teeth: 20}, 2: {teeth: 40}}
links: [{type: mesh, between: [1, 2]}, {type: coupling, between: [2, 3]}]
ports: [{component: 1, role: input}, {component: 3, role: output}]
""".replace("2: {teeth: 40}}", "2: {teeth: 40}, 3: {}}"))
    mesh, coupling = MODEL_SCHEMA["$defs"]["link"]["oneOf"][0], \
        MODEL_SCHEMA["$defs"]["link"]["oneOf"][2]
    assert MODEL_SCHEMA["properties"]["defaults"]["properties"]["mesh_efficiency"][
        "default"] == model.links[0].efficiency == 1.0
    assert coupling["properties"]["efficiency"]["default"] == model.links[1].efficiency
    component = MODEL_SCHEMA["$defs"]["component"]["properties"]
    assert component["count"]["default"] == model.components["1"].count == 1
    assert component["internal"]["default"] is model.components["1"].internal is False
    assert "carrier" in mesh["properties"] and model.links[0].carrier == "0"


@pytest.mark.parametrize("path", MODELS, ids=[p.stem for p in MODELS])
def test_every_library_model_satisfies_the_schema(path: Path) -> None:
    data = yaml.safe_load(path.read_text())
    errors = [e.message for e in VALIDATOR.iter_errors(as_json(data))]
    assert errors == []
    load_model(path)


RV = yaml.safe_load((ROOT / "models" / "rv40e_wang2021.yaml").read_text())


def mutated(change) -> dict:
    data = copy.deepcopy(RV)
    change(data)
    return data


# Format mistakes (each breaks the schema) and the place the program names.
FORMAT_MISTAKES = {
    "unknown top field": (lambda d: d.update(link=[]), "link"),
    "unknown component field": (lambda d: d["components"][1].update(teth=3),
                                "components.1.teth"),
    "teeth zero": (lambda d: d["components"][1].update(teeth=0), "components.1.teeth"),
    "teeth fraction": (lambda d: d["components"][1].update(teeth=12.5),
                       "components.1.teeth"),
    "teeth huge": (lambda d: d["components"][1].update(teeth=10 ** 30), "components.1.teeth"),
    "count bool": (lambda d: d["components"][2].update(count=True), "components.2.count"),
    "role": (lambda d: d["components"][1].update(role="ground"), "components.1.role"),
    "link type": (lambda d: d["links"][0].update(type="belt"), "links[0].type"),
    "link without type": (lambda d: d["links"][0].pop("type"), "links[0].type"),
    "fixed with efficiency": (lambda d: d["links"][2].update(efficiency=0.9),
                              "links[2].efficiency"),
    "efficiency above one": (lambda d: d["links"][0].update(efficiency=1.5),
                             "links[0].efficiency"),
    "efficiency nan": (lambda d: d["links"][0].update(efficiency=math.nan),
                       "links[0].efficiency"),
    "ratio zero": (lambda d: d["links"][0].update(ratio=0), "links[0].ratio"),
    "ratio tiny": (lambda d: d["links"][0].update(ratio=1e-308), "links[0].ratio"),
    "between three": (lambda d: d["links"][0].update(between=[1, 2, 3]), "links[0].between"),
    "backlash_arcmin huge": (lambda d: d["links"][1].update(backlash_arcmin=1e308),
                             "links[1].backlash_arcmin"),
    "port role": (lambda d: d["ports"][0].update(role="motor"), "ports[0].role"),
    "port power huge": (lambda d: d["ports"][0].update(power=1e308), "ports[0].power"),
    "port speed inf": (lambda d: d["ports"][0].update(speed=math.inf), "ports[0].speed"),
    "port torque text": (lambda d: d["ports"][1].update(torque=[1]), "ports[1].torque"),
    "name empty": (lambda d: d.update(name=" "), "name"),
    "components list": (lambda d: d.update(components=[1, 2]), "components"),
}


@pytest.mark.parametrize("name", list(FORMAT_MISTAKES))
def test_format_mistakes_are_refused_by_the_program_and_by_jsonschema(name: str) -> None:
    change, place = FORMAT_MISTAKES[name]
    data = mutated(change)
    with pytest.raises(ModelError) as info:
        model_from_dict(data)
    assert info.value.path == place, str(info.value)
    if not any(isinstance(v, float) and not math.isfinite(v)
               for v in (data["ports"][0].get("speed", 0), data["links"][0].get(
                   "efficiency", 0))):  # JSON has no inf/nan: nothing to compare there
        assert not VALIDATOR.is_valid(as_json(data)), name


def test_geometry_without_shape_on_a_toothed_component_is_a_gear() -> None:
    text = """
name: t
components:
  0: {role: frame}
  1: {teeth: 12, geometry: {module: 1.5, face_width: 12 mm, bore_radius: 0}}
  2: {teeth: 36, geometry: GEOMETRY}
links: [{type: mesh, between: [1, 2]}]
ports: [{component: 1, role: input}, {component: 2, role: output}]
"""
    model = loads_model(text.replace("GEOMETRY", "{module: 1.5, face_width: 12, "
                                                 "bore_radius: 5}"))
    assert model.components["1"].geometry.shape == "gear"
    # z = 36, m = 1.5: root radius 1.5*36/2 - 1.25*1.5 = 25.125 mm
    assert model.components["2"].geometry.root_radius(36) == pytest.approx(25.125)
    data = as_json(yaml.safe_load(text.replace("GEOMETRY", "{module: 1, face_width: 1, "
                                                           "bore_radius: 0}")))
    assert VALIDATOR.is_valid(data)
    with pytest.raises(ModelError) as info:  # no teeth: the shape cannot be guessed
        loads_model(text.replace("{teeth: 36, geometry: GEOMETRY}",
                                 "{geometry: {module: 1, face_width: 1, bore_radius: 0}}")
                    .replace("links: [{type: mesh, between: [1, 2]}]",
                             "links: [{type: coupling, between: [1, 2]}]"))
    assert info.value.path == "components.2.geometry.shape"


def test_unknown_field_message_lists_the_fields_allowed_there() -> None:
    with pytest.raises(ModelError) as info:
        model_from_dict(mutated(lambda d: d["links"][2].update(carrier=0)))
    assert info.value.path == "links[2].carrier"
    assert re.fullmatch(r"unknown field \(allowed: between, name, note, type\)",
                        info.value.message)


def test_a_model_without_geometry_reads_no_geometry_schema() -> None:
    """Start-up: the geometry definition (written from the shapes' dataclasses) is looked
    up only by a model with a geometry block; the whole schema still holds it."""
    import subprocess
    import sys

    code = ("import sys, powergraph as pg; pg.load_model('models/wolfrom_3k.yaml');"
            "print('powergraph.model.block_geometry' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=ROOT, check=True).stdout.split()
    assert out == ["False"]
    assert MODEL_SCHEMA["$defs"]["geometry"]["oneOf"]
