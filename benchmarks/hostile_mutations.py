"""Mutation classes of benchmarks/hostile_inputs.py and tests/cli/test_hostile.py.

Each class turns a library model's text into a hostile variant and says what is expected:
``"any"`` (exit 0 or 2, one line, no traceback, no hang) or ``"same"`` (the mutation does
not change the train: the answer must equal the plain model's). ``CLASSES`` lists them;
``mutate(name, text, rng)`` applies one. At the end, the mutations of the modes table,
shift elements and machine ports that benchmarks/hostile_tables.py puts in its cases.
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
    ports = data.get("ports") if isinstance(data.get("ports"), list) else []
    names = {str(p.get("name")) for p in ports if isinstance(p, dict)}   # a port's name
    taken = {str(k) for k in components} | names     # may not be another component's id
    new = rng.choice([i for i in ODD_IDS if i not in taken])
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


# --- modes and machines (benchmarks/hostile_tables.py puts them in files with tables) -----
#: Mode names as written in the file: mathtext, YAML 1.1 booleans and nulls (unquoted),
#: numbers, odd text.
MODE_NAMES = ["$x$", "$\\frac{1}{0}$", "$", "$$", "$\\undefinedcommand$", "a$b$c", "$^$",
              "off", "on", "yes", "no", "y", "n", "true", "False", "~", "null", "1.0", "01",
              "0x1", "1e3", ".inf", "' '", "-", "--mode", "-1", "日本", "'a,b'", "\"a\\nb\"",
              "x" * 300, "'#'", "'%'", "'R '", "'\"'", "\"\\t\"", "'{'", "'1:2'"]
#: Port and element names: mathtext and text that draws badly.
ODD_NAMES = ["$\\omega$", "$", "$x", "$\\frac{a$", "$^$", "$\\undefinedcommand$", "a$b$c",
             "\\", "%", "{}", "_", "MG1\nMG2", "", " ", "x" * 500, "日本", "\x1b[31m"]
JUNK_HOLDS = ["maybe", None, 1, ["positive"], "Positive", True, "both", "", {"a": 1}]
JUNK_EFFICIENCY = [0, 1e-300, 1.5, 1.0000001, -0.9, ".nan", ".inf", "90 %", "0.9 W", "",
                   [], {}, True, "1e400", 5e-7, 1e-6, {"map": "x.csv", "extra": 1},
                   {"mapp": "x.csv"}]
JUNK_BATTERY = ["1e308 W", ".nan", "nan W", "x", "-1e400 W", "5 rpm", [], {}, "FREE", None,
                0, "0", True, "1 W**99999", "inf W", "-1e308 W", "1e-300 W", 1e308]
JUNK_MAX_SPEED = ["13500 rpm", "-1 rpm", "0 rpm", ".nan", "fast", "1e400 rpm", "13500 N*m",
                  13500, [], "inf rpm", "1e-300 rpm", "1 rpm", "1e308 rad/s", None, "-0 rpm"]


def _fast(text: str) -> Any:
    return yaml.load(text, Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader))


def _fast_dump(data: Any) -> str:
    return yaml.dump(data, Dumper=getattr(yaml, "CSafeDumper", yaml.SafeDumper),
                     sort_keys=False, allow_unicode=True, width=10**9)


def typed_name(raw: str) -> str:
    """The name as one types it on the command line (``--mode on``): the parsed key when
    it is text, else the text as written."""
    key = next(iter(_fast(f"{raw}: 1") or {None: 1}))
    return key if isinstance(key, str) else raw


def _frame_id(data: dict) -> Any:
    return next((k for k, v in data["components"].items()
                 if isinstance(v, dict) and v.get("role") == "frame"), 0)


def _with_modes(data: dict, modes: list[tuple[str, Any]]) -> str:
    """The model with its ``modes:`` block written by hand: keys as given (unquoted
    booleans, repeated keys), values in flow style."""
    rest = {k: v for k, v in data.items() if k != "modes"}
    return _fast_dump(rest) + "modes:\n" + "".join(f"  {k}: {_flow(v)}\n" for k, v in modes)


def mode_names(text: str, rng: random.Random):
    """Modes renamed (mathtext, YAML booleans, numbers) or two modes of one name."""
    data = _fast(text)
    modes = [(_flow(str(k)), v) for k, v in data["modes"].items()]
    how = rng.choice(["rename", "rename", "rename-all", "repeat", "int-and-str"])
    if how == "repeat":
        modes.append(rng.choice(modes))
    elif how == "int-and-str":
        modes += [("1", modes[0][1]), ("'1'", modes[-1][1])]
    else:
        which = range(len(modes)) if how == "rename-all" else [rng.randrange(len(modes))]
        for i, name in zip(which, rng.sample(MODE_NAMES, len(which))):
            modes[i] = (name, modes[i][1])
    return _with_modes(data, modes), how


def mode_tables(text: str, rng: random.Random):
    """Engaged-element lists with unknown, repeated or freewheel names, empty, not lists;
    the table empty, not a mapping, or many modes."""
    data = _fast(text)
    modes = [(_flow(str(k)), list(v)) for k, v in data["modes"].items()]
    names = [str(link.get("name")) for link in data["links"] if "name" in link]
    i = rng.randrange(len(modes))
    how = rng.choice(["unknown", "repeat", "empty", "not-a-list", "table", "freewheel",
                      "everything", "one-less", "many"])
    if how == "unknown":
        modes[i][1].append(rng.choice(["X", "c1", "0", 1, None, names[0] + " ", "", [names[0]],
                                       {"a": 1}, "$x$", True]))
    elif how == "repeat":
        modes[i][1].append(modes[i][1][0] if modes[i][1] else names[0])
    elif how in ("empty", "not-a-list"):
        value = [] if how == "empty" else rng.choice([None, "", names[0], 5, {}, {"a": 1},
                                                      [[names[0]]]])
        modes[i] = (modes[i][0], value)
    elif how == "table":
        rest = {k: v for k, v in data.items() if k != "modes"}
        junk = rng.choice(["{}", "[]", "~", "x", "[[C1]]", "5"])
        return _fast_dump(rest) + f"modes: {junk}\n", how
    elif how == "freewheel":
        data["links"].append({"type": "freewheel", "name": "FX", "between":
                              list(data["links"][-1]["between"]), "holds": "positive"})
        modes[i][1].append("FX")
    elif how == "everything":
        modes[i] = (modes[i][0], names)
    elif how == "one-less" and modes[i][1]:
        modes[i][1].pop(rng.randrange(len(modes[i][1])))
    elif how == "many":
        modes = [(f"'{n}'", modes[n % len(modes)][1]) for n in range(rng.choice([30, 60]))]
    return _with_modes(data, modes), how


def shift_elements(text: str, rng: random.Random):
    """Many parallel freewheels, ``holds`` junk, repeated element names, an element on
    one member or the frame twice, junk drag, and a zero input load."""
    data = _fast(text)
    links, frame = data["links"], _frame_id(data)
    shift = [link for link in links if link.get("type") in ("clutch", "brake", "freewheel")]
    element = rng.choice(shift)
    how = rng.choice(["freewheels", "freewheels", "freewheels-spread", "holds", "same-name",
                      "one-member", "frame-frame", "drag", "engaged", "zero-load", "zero-load"])
    if how.startswith("freewheels"):
        members = [k for k in data["components"] if str(k)[:1] in "src"] + [frame]
        for k in range(rng.choice([2, 3, 5, 8, 12, 16, 20])):
            pair = element["between"] if how == "freewheels" else rng.sample(members, 2)
            links.append({"type": "freewheel", "name": f"FW{k}", "between": list(pair),
                          "holds": rng.choice(["positive", "negative"])})
    elif how == "holds":
        free = [link for link in shift if link.get("type") == "freewheel"] or [element]
        target = rng.choice(free)
        target.update(type="freewheel", holds=rng.choice(JUNK_HOLDS))
        if target["holds"] is None:
            del target["holds"]
    elif how == "same-name":
        element["name"] = rng.choice([e for e in shift if e is not element] or shift)["name"]
    elif how in ("one-member", "frame-frame"):
        element["between"] = [element["between"][0] if how == "one-member" else frame] * 2
    elif how == "drag":
        element["drag"] = rng.choice([{"no_load_torque": "1e308 N*m"}, -1, "x",
                                      {"a": "1 N*m", "b": "1e300 N*m"}, {"a": ".nan"},
                                      {"no_load_torque": "-5 N*m"}, {}])
    elif how == "engaged":
        element["engaged"] = rng.choice(["yes", 1, None, [], "maybe"])
    else:
        port = next(p for p in data["ports"] if p.get("role") == "input")
        port.pop("power", None)
        port.update(rng.choice([{"torque": "0 N*m"}, {"power": "0 kW"}, {"speed": "0 rpm"},
                                {"torque": "1e-300 N*m"}]))
    names = [(_flow(str(k)), v) for k, v in data["modes"].items()]
    return _with_modes(data, names), how


def machine_ports(text: str, rng: random.Random):
    """Machines with repeated names, names of other ports' components or mathtext, junk
    efficiency, bus, battery, buses or max_speed; two machines on one body."""
    data = _fast(text)
    ports = data["ports"]
    machines = [p for p in ports if p.get("role") == "machine"]
    port = rng.choice(machines)
    other = rng.choice([p for p in ports if p is not port])
    how = rng.choice(["same-name", "component-name", "odd-name", "efficiency", "no-bus",
                      "bus", "battery", "buses", "max-speed", "max-speed", "one-body",
                      "loads"])
    field, value = {
        "same-name": ("name", other.get("name", str(other["component"]))),
        "component-name": ("name", str(other["component"])),
        "odd-name": ("name", ODD_NAMES), "efficiency": ("efficiency", JUNK_EFFICIENCY),
        "bus": ("bus", ["ac", None, [], {}, 5, "", "$x$"]), "max-speed": ("max_speed",
                                                                          JUNK_MAX_SPEED),
        "one-body": ("component", other["component"])}.get(how, (None, None))
    if field:
        target = other if how == "max-speed" and rng.random() < 0.2 else port
        target[field] = rng.choice(value) if isinstance(value, list) else value
    elif how == "no-bus":
        port.pop("bus", None)
    elif how == "battery":
        data["buses"] = {k: {"battery": rng.choice(JUNK_BATTERY)} for k in data["buses"]}
    elif how == "buses":
        data["buses"] = rng.choice([[], None, "dc", {"dc": 5}, {"dc": {"battery": "0 W",
                                    "x": 1}}, {**data["buses"], "spare": {"battery": "0 W"}},
                                    {"dc": None}])
    else:
        port.update(rng.choice([{"power": "5 kW"}, {"torque": "1e308 N*m"}, {"speed": "0 rpm"},
                                {"role": "Machine"}, {"role": "machine", "bus": "dc",
                                                      "component": _frame_id(data)}]))
    return _fast_dump(data), how
