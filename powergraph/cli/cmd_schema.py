"""``powergraph schema``: print the JSON Schema of model files (draft 2020-12).

Point an editor's YAML language server at it for completion and checking as you type
(docs/format.md): ``powergraph schema > powergraph.schema.json``.
"""
from __future__ import annotations

import argparse
import json
import sys


def register(sub: argparse._SubParsersAction) -> None:
    parser = sub.add_parser("schema", help="print the JSON Schema of model files",
                            description="Print the JSON Schema (draft 2020-12) of model "
                                        "files, for editors: powergraph schema > "
                                        "powergraph.schema.json")
    parser.set_defaults(handler=run)


def schema_text() -> str:
    """The schema as the JSON text ``powergraph schema`` prints (ends with a newline).

    >>> '"$schema"' in schema_text()
    True
    """
    from powergraph.model.schema import MODEL_SCHEMA

    return json.dumps(MODEL_SCHEMA, indent=2, ensure_ascii=False) + "\n"


def run(args: argparse.Namespace) -> int:
    sys.stdout.write(schema_text())
    return 0
