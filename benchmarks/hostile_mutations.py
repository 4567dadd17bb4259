"""Mutation classes of benchmarks/hostile_inputs.py and tests/cli/test_hostile.py.

Each class turns a library model's text into a hostile variant and says what is expected:
``"any"`` (exit 0 or 2, one line, no traceback, no hang) or ``"same"`` (the mutation does
not change the train: the answer must equal the plain model's). ``CLASSES`` lists them;
``mutate(name, text, rng)`` applies one.
"""
from __future__ import annotations

import math
import random
import re
from typing import Any, Callable

import yaml

JUNK_VALUES = ["1e308", "-1e308", ".nan", ".inf", "-.inf", "1e-308", "0", "-1", "9" * 400,
               "[]", "{}", "~", "true", "'x'", "*a", "&a [1, 2]", "[[[[[[[[", "!!binary aGk=",
               "!!python/object:os.system x", "1e400 rpm", "0.0", "2.5", "-0.0", "1 kg",
               "\"\\u0000\"", "[1, 2, 3]", "{a: 1}", "null", "0x7fffffffffffffffffff"]
YAML_TAGS = ["!!bool 'maybe'", "!!float ''", "!!int 'abc'", "!!binary aGk=", "!!binary '!!'",
             "!!timestamp 2001-12-14", "!!timestamp 'tomorrow'", "!unknown x", "!tag {a: 1}",
             "!!str 5", "!!float '1e400'", "!!int '9999999999999999999999999'", "!!null x",
             "!!map [1]", "!!seq {a: 1}", "!!set {a, b}", "!!omap [a: 1]",
             "!<tag:yaml.org,2002:int> '7'", "!!python/name:os.system ''"]
#: Unit expressions that must end quickly in exit 0 or 2 (never a hang or exit 1).
HOSTILE_UNITS = ["9**9**9 W", "1 W**99999", "2**2**2**2**2 rpm", "1 " + "k" * 2000 + "W",
                 "1 " + "m/" * 3000 + "s", "(" * 5000 + "1" + ")" * 5000 + " rpm",
                 "1 " + "rpm*" * 2000 + "rpm", "1e400 W", "-1e400 rpm", "1e-400 rpm",
                 "nan rpm", "inf W", "1 rpm rpm", "1 W/0", "0/0 W", "1_000 rpm", "1 ㎾",
                 "١٠٠٠ rpm", "1000 rpm" + " " * 100_000, "1000 r\u200bpm", "1000 °/s",
                 "1 1/min", "25 Hz", "1 1/0"]
#: Ids that collide with the flow graph's own names, or are unusual text.
ODD_IDS = ["motor", "generator", "loss", "ground", "mesh 1-2", "frame", "a/b", "sun gear",
           "ζ-ring", "日本", "x" * 200, "-", "0.5", "true", "null", "links", "loss 1"]
MISSING = object()

Mutation = Callable[[str, random.Random], tuple[str | bytes, str]]


def _lines(text: str) -> list[str]:
    return text.splitlines(keepends=True)


def _field_lines(lines: list[str]) -> list[int]:
    return [i for i, line in enumerate(lines) if ": " in line
            and not line.lstrip().startswith("#")]


def _replace_value(text: str, rng: random.Random, values: list[str]) -> str:
    lines = _lines(text)
    i = rng.choice(_field_lines(lines))
    head = lines[i].split(": ", 1)[0] if rng.random() < 0.5 else lines[i].rsplit(": ", 1)[0]
    lines[i] = f"{head}: {rng.choice(values)}\n"
    if "{" in head and "}" not in head:
        lines[i] = lines[i].rstrip("\n") + "}" * head.count("{") + "\n"
    if "[" in head and "]" not in head:
        lines[i] = lines[i].rstrip("\n") + "]" * head.count("[") + "\n"
    return "".join(lines)


# --- the earlier classes (kept as they were) ----------------------------------------------
def control(text: str, rng: random.Random):
    pos = rng.randrange(len(text))
    char = rng.choice(["\x00", "\x01", "\x1b", "\x7f", "\ufeff", "\x85", "\ud800"])
    return (text[:pos] + char + text[pos:]).encode("utf-8", "surrogatepass"), "any"


def bad_utf8(text: str, rng: random.Random):
    raw = bytearray(text.encode())
    raw[rng.randrange(len(raw))] = rng.choice([0xff, 0xc3, 0x80, 0xfe])
    return bytes(raw), "any"


def byte_flips(text: str, rng: random.Random):
    raw = bytearray(text.encode())
    for _ in range(rng.randint(1, 6)):
        raw[rng.randrange(len(raw))] = rng.randrange(256)
    return bytes(raw), "any"


def delete_line(text: str, rng: random.Random):
    lines = _lines(text)
    where = rng.randrange(len(lines))
    return "".join(lines[:where] + lines[where + 1:]), "any"


def duplicate_line(text: str, rng: random.Random):
    lines = _lines(text)
    where = rng.randrange(len(lines))
    return "".join(lines[:where + 1] + lines[where:]), "any"


def junk_value(text: str, rng: random.Random):
    return _replace_value(text, rng, JUNK_VALUES), "any"


def deep_nesting(text: str, rng: random.Random):
    depth = rng.choice([50, 99, 101, 1000, 100_000])
    return text + f"\nx: {'[' * depth}{']' * depth}\n", "any"


def huge_integers(text: str, rng: random.Random):
    return "".join(line.replace(": 1", ": 1" + "0" * rng.randint(20, 5000), 1)
                   for line in _lines(text)), "any"


def comment(text: str, rng: random.Random):
    return text + f"\n# {'x' * rng.randint(1, 200)}\n", "same"


# --- new classes -----------------------------------------------------------------------------
def yaml_tag(text: str, rng: random.Random):
    """An explicit YAML tag in place of a field's value."""
    return _replace_value(text, rng, YAML_TAGS), "any"


def hostile_unit(text: str, rng: random.Random):
    """A unit expression bomb (exponent towers, prefix runs, long products) as a port value."""
    data = _data(text)
    ports = [p for p in data.get("ports", []) if isinstance(p, dict)]
    if not ports:
        return _replace_value(text, rng, HOSTILE_UNITS), "any"
    port = rng.choice(ports)
    port[rng.choice(["speed", "power", "torque"])] = rng.choice(HOSTILE_UNITS)
    return _dump(data), "any"


def equivalent_unit(text: str, rng: random.Random):
    """A port speed in rpm written in rad/s, or a power in kW written in W: same train."""
    data = _data(text)
    for port in data.get("ports", []):
        for field, value in list(port.items()):
            match = re.fullmatch(r"\s*([-+0-9.eE]+)\s*(rpm|kW)\s*", str(value))
            if match and field in ("speed", "power"):
                number = float(match[1])
                port[field] = (f"{number * 2 * math.pi / 60!r} rad/s" if match[2] == "rpm"
                               else f"{number * 1000!r} W")
    return _dump(data), "same"


def frequency_unit(text: str, rng: random.Random):
    """A port speed in rpm written as a frequency (1/min, Hz): the same train."""
    data = _data(text)
    for port in data.get("ports", []):
        match = re.fullmatch(r"\s*([-+0-9.eE]+)\s*rpm\s*", str(port.get("speed", "")))
        if match:
            number = float(match[1])
            port["speed"] = rng.choice([f"{number!r} 1/min", f"{number / 60!r} Hz"])
    return _dump(data), "same"


def rename_id(text: str, rng: random.Random):
    """A component id renamed everywhere to a reserved word of the flow graph or odd text."""
    data = _data(text)
    components = data.get("components")
    if not isinstance(components, dict):
        return text, "same"
    old = rng.choice(list(components))
    new = rng.choice([i for i in ODD_IDS if i not in {str(k) for k in components}])
    renamed = _renamed(data, old, new)
    return (_dump(renamed), "same") if renamed is not None else (text, "same")


def merge_same(text: str, rng: random.Random):
    """A link written as a YAML merge of an anchored link, every merged field overridden
    (or as a merge of its own fields): the same train."""
    data = _data(text)
    links = data.get("links", [])
    if len(links) < 1:
        return text, "same"
    j = rng.randrange(len(links))
    # a donor before the link: an alias after its anchor needs no reordering of the links,
    # whose indices tolerances and PATHs refer to
    donors = [i for i in range(j) if set(links[i]) <= set(links[j])]
    return _merge_text(data, j, donors[0] if donors else None), "same"


def merge_override(text: str, rng: random.Random):
    """A link merging another link's fields, overriding some: any train, never a crash."""
    data = _data(text)
    links = data.get("links", [])
    if len(links) < 2:
        return text, "any"
    j, donor = rng.sample(range(len(links)), 2)
    keep = {k: v for k, v in links[j].items() if rng.random() < 0.5}
    data["links"][j] = keep
    return _merge_text(data, j, donor), "any"


CLASSES: dict[str, Mutation] = {
    "control": control, "bad-utf8": bad_utf8, "byte-flips": byte_flips,
    "delete-line": delete_line, "duplicate-line": duplicate_line, "junk-value": junk_value,
    "deep-nesting": deep_nesting, "huge-integers": huge_integers, "comment": comment,
    "yaml-tag": yaml_tag, "hostile-unit": hostile_unit, "equivalent-unit": equivalent_unit,
    "frequency-unit": frequency_unit, "rename-id": rename_id, "merge-same": merge_same,
    "merge-override": merge_override,
}


def mutate(name: str, text: str, rng: random.Random) -> tuple[bytes, str]:
    """(file bytes, expectation) of class ``name`` applied to ``text``."""
    out, expect = CLASSES[name](text, rng)
    return (out if isinstance(out, bytes) else out.encode("utf-8", "surrogatepass")), expect


# --- helpers: data in, YAML out ------------------------------------------------------------
def _data(text: str) -> Any:
    return yaml.safe_load(text)


def _dump(data: Any) -> str:
    return yaml.safe_dump(data, sort_keys=False, allow_unicode=True, width=10**9)


def _renamed(data: Any, old: Any, new: str) -> Any | None:
    """``data`` with component ``old`` called ``new`` in every reference; None where a
    reference could not be told from other text (the rename is then skipped)."""
    components = data["components"]
    data = dict(data, components={(new if k == old else k): v for k, v in components.items()})
    hits = [0]

    def swap(value: Any, key: str | None) -> Any:
        if isinstance(value, dict):
            hits[0] += any(str(k) == str(old) for k in value)  # an id as a key: not renamed
            return {k: swap(v, k) for k, v in value.items()}
        if isinstance(value, list):
            return [swap(v, key) for v in value]
        if value == old and type(value) is type(old) and key in REFERENCES:
            return new
        if value == old or (isinstance(value, str) and str(old) in value.split(".")):
            hits[0] += 1
        return value

    out = {k: (swap(v, k) if k in ("links", "ports") else v) for k, v in data.items()}
    out["components"] = {k: swap(v, None) for k, v in data["components"].items()}
    if hits[0] or "tolerances" in data:
        return None
    return out


#: Keys whose values are component ids (docs/format.md).
REFERENCES = {"between", "carrier", "component", "sun", "planet", "crank", "disc", "ring",
              "pin", "output", "input"}


def _merge_text(data: dict, j: int, donor: int | None) -> str:
    """The document in flow style, ``links[j]`` written as ``{<<: *d, ...}`` (anchor on
    ``links[donor]``) or, without a donor, ``{<<: {its fields}}``."""
    links = []
    for i, link in enumerate(data["links"]):
        body = _flow(link)
        if i == donor:
            body = f"&d {body}"
        if i == j:
            own = ", ".join(f"{_flow(k)}: {_flow(v)}" for k, v in link.items())
            body = (f"{{<<: *d{', ' + own if own else ''}}}" if donor is not None
                    else f"{{<<: {_flow(link)}}}")
        links.append(body)
    if donor is not None and donor > j:   # an alias must follow its anchor
        return _merge_text_ordered(data, j, donor)
    rest = {k: v for k, v in data.items() if k != "links"}
    return _dump(rest) + "links:\n" + "".join(f"  - {body}\n" for body in links)


def _merge_text_ordered(data: dict, j: int, donor: int) -> str:
    """As :func:`_merge_text` when the donor comes later: the donor moves just before
    ``links[j]`` (the order of links does not change the train)."""
    links = list(data["links"])
    links.insert(j, links.pop(donor))        # donor now at j, the merged link at j + 1
    return _merge_text(dict(data, links=links), j + 1, j)


def _flow(value: Any) -> str:
    """One value as YAML flow text."""
    if isinstance(value, dict):
        return "{" + ", ".join(f"{_flow(k)}: {_flow(v)}" for k, v in value.items()) + "}"
    if isinstance(value, list):
        return "[" + ", ".join(_flow(v) for v in value) + "]"
    text = yaml.safe_dump(value, default_flow_style=True, width=10**9, allow_unicode=True)
    return text.removesuffix("\n...\n").strip()
