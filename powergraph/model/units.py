"""Physical quantities in model files: plain SI numbers or strings with units.

A quantity string is read with a small grammar of our own before any unit library sees
it (:func:`unit_expression`): a decimal number, then unit names joined by ``*``, ``/``,
``·`` or spaces, with small integer powers (``^2``, ``**-1``) and shallow parentheses, in
at most :data:`MAX_TEXT` characters. Anything else is refused at once, so a hostile string
(``9**9**9 W``, a unit with hundreds of prefixes) cannot keep pint busy.

Everyday units (rpm, rad/s, Hz, W, kW, N*m, ...; :func:`accepted_units`) are converted
from a small table, so `powergraph solve` does not pay pint's start-up time; anything else
is handed to pint (the test-suite checks the table against it). **Case**: a unit of the
table is read in any case when that names one unit of its kind (``kw``, ``KW`` -> kW;
``RPM`` -> rpm; ``nm`` -> N*m); where case tells two apart (``mw``: mW or MW) the text is
refused, naming both; any other unit is pint's, spelled as pint spells it. Every place
that reads a unit follows this (:func:`unit_factor` for a table's column header).

Speeds follow one rule (:func:`speed_in_rad_s`): a unit that names an angle (``rad/s``,
``deg/s``, ``rev/min``, ``turn/s``) converts through that angle; a unit of frequency
without an angle (``Hz``, ``1/min``, ``s^-1``) counts revolutions, so ω = 2π·f.

Examples
--------
>>> parse_quantity("1500 rpm", "speed", "ports[0].speed")
157.07963267948966
>>> parse_quantity("2.27 kW", "power", "ports[0].power")
2270.0
>>> parse_quantity(12.5, "torque", "ports[1].torque")
12.5
>>> round(parse_quantity("50 Hz", "speed", "ports[0].speed"), 6)
314.159265
"""
from __future__ import annotations

import math
import re
from functools import lru_cache

from powergraph.errors import Caveat, ModelError
from powergraph.model.yaml_loader import brief
from powergraph.units_si import RAD_S_PER_RPM

#: SI unit of each kind of quantity a model may carry.
SI_UNITS = {"speed": "rad/s", "power": "W", "torque": "N*m", "length": "mm",
            "kinematic viscosity": "m^2/s", "density": "kg/m^3", "area": "m^2",
            "heat transfer coefficient": "W/(m^2*K)", "volume": "m^3"}
#: Longest quantity string read, and longest unit name in it.
MAX_TEXT, MAX_NAME = 64, 24
#: Largest power of a unit (``m^4``) and deepest parentheses in a quantity string.
MAX_POWER, MAX_PARENS = 4, 2

_RPM, _TURN = RAD_S_PER_RPM, 2 * math.pi
# Units read without pint, per kind: (spellings, factor to TABLE_UNITS[kind]); messages
# show the first spelling. The grammar spells "N·m", "N m" as "N*m", so only juxtapositions
# ("Nm") need entries. Both units of a case pair (mW, MW) are listed, so that another case
# is known to be ambiguous. Speeds obey speed_in_rad_s's rule (Hz is revolutions per s).
_TABLES = {
    "speed": ((("rad/s",), 1.0), (("rad/min",), 1 / 60), (("deg/s", "°/s"), math.pi / 180),
              (("rpm", "rev/min", "r/min"), _RPM), (("rps", "rev/s", "turn/s"), _TURN),
              (("Hz", "1/s", "s^-1"), _TURN), (("kHz",), 1e3 * _TURN),
              (("1/min", "/min", "min^-1"), _RPM), (("1/h",), _TURN / 3600)),
    "power": ((("W",), 1.0), (("kW",), 1e3), (("mW",), 1e-3), (("MW",), 1e6),
              (("hp",), 745.69987158227022)),
    "torque": ((("N*m", "Nm"), 1.0), (("kN*m", "kNm"), 1e3), (("mN*m", "mNm"), 1e-3),
               (("MN*m", "MNm"), 1e6), (("N*mm", "Nmm"), 1e-3)),
    "length": ((("mm",), 1.0), (("m",), 1e3), (("cm",), 10.0), (("um", "µm"), 1e-3),
               (("Mm",), 1e9)),
    "dynamic viscosity": ((("mPa*s", "cP"), 1.0), (("Pa*s",), 1e3), (("MPa*s",), 1e9)),
    "kinematic viscosity": ((("cSt", "mm^2/s"), 1e-6), (("m^2/s",), 1.0),
                            (("St", "cm^2/s"), 1e-4)),
    "density": ((("kg/m^3",), 1.0), (("g/cm^3", "kg/L", "g/mL"), 1e3), (("g/L",), 1.0)),
    "area": ((("m^2",), 1.0), (("mm^2",), 1e-6), (("cm^2",), 1e-4), (("dm^2",), 1e-2)),
    "volume": ((("m^3",), 1.0), (("L", "l", "dm^3"), 1e-3), (("cm^3", "mL", "ml"), 1e-6),
               (("mm^3",), 1e-9)),
    "heat transfer coefficient": ((("W/(m^2*K)", "W/m^2/K"), 1.0),
                                  (("kW/(m^2*K)",), 1e3)),
}
#: Temperature units (``80 degC``): name -> (factor, offset) to kelvin.
TEMPERATURE_UNITS = {"K": (1.0, 0.0), "kelvin": (1.0, 0.0), "degC": (1.0, 273.15),
                     "°C": (1.0, 273.15), "celsius": (1.0, 273.15),
                     "degF": (5 / 9, 273.15 - 32 * 5 / 9), "°F": (5 / 9, 273.15 - 32 * 5 / 9)}
#: The unit the factors of each table lead to.
TABLE_UNITS = {**SI_UNITS, "dynamic viscosity": "mPa*s"}
_NUMBER_UNIT = re.compile(r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)(?:\s+|(?=\D)|$)"
                          r"(.*?)\s*", re.DOTALL)
# One token of a unit expression: a name, the factor 1, an operator, a power, a parenthesis.
_TOKEN = re.compile(r"\s*(?:(?P<name>(?:[^\W\d_]|°)(?:[^\W\d]|°)*)|(?P<one>1(?![\d.]))"
                    r"|(?P<op>[*/·⋅.])(?!\*)"
                    r"|(?P<pow>(?:\^|\*\*)(?:\((?P<inner>[-+]?\d+)\)|(?P<power>[-+]?\d+)))"
                    r"|(?P<paren>[()]))")
# Names pint does not know under these spellings.
_ALIASES = {"rev": "revolution", "revs": "revolution", "r": "revolution", "μm": "µm"}


def parse_quantity(value: object, kind: str, path: str) -> float:
    """Convert a model value to SI (rad/s, W, N*m) or mm for lengths.

    Parameters
    ----------
    value : int, float or str
        A number (already SI) or a string such as ``"1500 rpm"``.
    kind : {"speed", "power", "torque", "length"}
        What the value measures; the unit must have that dimension.
    path : str
        Place in the model file, for error messages.

    Returns
    -------
    float

    Raises
    ------
    ModelError
        Unknown unit, wrong dimension, not a number, or text outside the grammar.

    Examples
    --------
    >>> round(parse_quantity("120 N*m", "torque", "x"), 9)
    120.0
    >>> parse_quantity("9**9**9 W", "power", "ports[0].power")
    Traceback (most recent call last):
    ...
    powergraph.errors.ModelError: ports[0].power: cannot read '9**9**9 W' as a power: \
'**9' needs a unit before it
    """
    if isinstance(value, bool):
        raise ModelError(f"expected a {kind}, got {brief(value)}", path)
    if isinstance(value, (int, float)):
        try:
            result = float(value)
        except OverflowError:
            digits = int(value.bit_length() * math.log10(2)) + 1  # str() may refuse it
            raise ModelError(f"{kind} is out of range, got an integer of about {digits} "
                             "digits", path) from None
    elif isinstance(value, str):
        result = _parse_string(value, kind, path)
    else:
        raise ModelError(f"expected a {kind} (number or string with units), got {brief(value)}",
                         path)
    if not math.isfinite(result):
        raise ModelError(f"{kind} must be finite, got {brief(value)}", path)
    return result


def parse_temperature(value: object, path: str) -> float:
    """A temperature in kelvin: a number (K) or a string in K, degC (°C) or degF (°F).

    >>> parse_temperature("80 degC", "x"), parse_temperature(353.15, "x")
    (353.15, 353.15)
    >>> parse_temperature("80 C", "lubricant.temperature")
    Traceback (most recent call last):
    ...
    powergraph.errors.ModelError: lubricant.temperature: cannot read '80 C' as a temperature: write it in K, degC (°C) or degF (°F)
    """
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise ModelError(f"expected a temperature, got {brief(value)}", path)
    if isinstance(value, str):
        if len(value) > MAX_TEXT:
            raise ModelError(f"cannot read {brief(value)} as a temperature", path)
        number, unit = _split(value, "temperature", path)
        if unit.strip() not in TEMPERATURE_UNITS:
            raise ModelError(f"cannot read {value!r} as a temperature: write it in K, degC "
                             "(°C) or degF (°F)", path)
        factor, offset = TEMPERATURE_UNITS[unit.strip()]
        value = number * factor + offset
    kelvin = float(value)
    if not (math.isfinite(kelvin) and kelvin > 0.0):
        raise ModelError(f"a temperature must be above absolute zero, got {brief(value)}",
                         path)
    return kelvin


def parse_number(value: object, path: str, minimum: float | None = None,
                 positive: bool = False, length: bool = False) -> float:
    """A finite number from a model block (a length may also be a string with units).

    >>> parse_number("5 um", "x", positive=True, length=True)
    0.005
    >>> parse_number(-1, "links[0].backlash_arcmin", minimum=0.0)
    Traceback (most recent call last):
    ...
    powergraph.errors.ModelError: links[0].backlash_arcmin: must be >= 0, got -1
    """
    if length and isinstance(value, str):
        number = parse_quantity(value, "length", path)
    elif isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ModelError(f"must be a number, got {value!r}", path)
    else:
        number = float(value)
    if not math.isfinite(number):
        raise ModelError(f"must be finite, got {value!r}", path)
    if positive and number <= 0:
        raise ModelError(f"must be > 0, got {value!r}", path)
    if minimum is not None and number < minimum:
        raise ModelError(f"must be >= {minimum:g}, got {value!r}", path)
    return number


def parse_in_unit(text: str, unit: str, what: str, path: str) -> float:
    """A quantity string converted to ``unit`` (through the grammar, then pint).

    >>> parse_in_unit("0.03 Pa*s", "mPa*s", "dynamic viscosity", "x")
    30.0
    """
    number, written = _split(text, what, path)
    if not written:
        return number
    if TABLE_UNITS.get(what) == unit:
        factor, spelled = _lookup(written, what, what, text, path)
    else:
        factor, spelled = None, unit_expression(written, what, path, text)
    if factor is not None:
        return number * factor
    return _convert(number, spelled, unit, text, what, path)


def unit_factor(unit: str, kind: str, where: str) -> float:
    """The SI value of one ``unit`` of ``kind`` (mm for a length), read as a model's
    quantities are (the **Case** rule above; a speed by :func:`speed_in_rad_s`'s rule): a
    table's column header (``engine.speed [RPM]``) checks its unit once, then scales.
    Otherwise a :class:`ModelError` at ``where`` (an empty, unknown or ambiguous unit, or
    one of another dimension) listing the units accepted for ``kind``.

    >>> unit_factor("RPM", "speed", "x") == math.pi / 30, unit_factor("kw", "power", "x")
    (True, 1000.0)
    >>> unit_factor("mw", "power", "points.csv line 1, 'engine.power [mw]'")
    Traceback (most recent call last):
    ...
    powergraph.errors.ModelError: points.csv line 1, 'engine.power [mw]': cannot read 'mw' \
as a power: 'mw' could be mW or MW; write the unit with its exact case
    """
    if not isinstance(unit, str) or not unit.strip():
        raise ModelError(f"no unit given: {accepted_units(kind)}", where)
    if len(unit) > MAX_TEXT:
        raise _refuse(unit, kind, f"longer than {MAX_TEXT} characters", where)
    return _si(1.0, unit.strip(), kind, unit.strip(), where)


def accepted_units(kind: str) -> str:
    """The units read for ``kind`` without pint, for messages and docs/format.md.

    >>> accepted_units("power")
    'a power is written in W, kW, mW, MW or hp (in any case, unless the case tells two \
apart), or in any unit pint knows, spelled as pint spells it'
    """
    pint = "any unit pint knows, spelled as pint spells it"
    if kind not in _TABLES:
        return f"a {kind} is written in {pint}"
    names = [spellings[0] + (f" ({', '.join(spellings[1:])})" if spellings[1:] else "")
             for spellings, _ in _TABLES[kind]]
    return (f"a {kind} is written in {', '.join(names[:-1])} or {names[-1]} (in any case, "
            f"unless the case tells two apart), or in {pint}")


def speed_in_rad_s(number: float, unit: str, text: str = "", path: str = "") -> float:
    """The one rule for speeds: ``number`` in ``unit`` as rad/s.

    A unit that names an angle (rad/s, deg/s, rev/min, rpm, turn/s) converts through that
    angle; a frequency without an angle (Hz, kHz, 1/s, 1/min, s^-1) counts revolutions per
    time, so ω = 2π·f. ``unit`` is checked by :func:`unit_expression` first.

    >>> speed_in_rad_s(3000, "1/min") == speed_in_rad_s(3000, "rpm") == 100 * math.pi
    True
    >>> speed_in_rad_s(1, "rad/s")
    1.0
    """
    text = text or f"{number:g} {unit}"
    factor, spelled = _lookup(unit, "speed", "speed", text, path)
    if factor is not None:
        return number * factor
    quantity = _pint_quantity(number, spelled, text, "speed", path)
    if quantity.dimensionality != _registry().parse_units("Hz").dimensionality:
        raise ModelError(f"{brief(text)} is not a speed: {accepted_units('speed')}", path)
    root = quantity.to_root_units()
    units = dict(root.unit_items())
    if units == {"second": -1}:
        return float(root.magnitude) * 2 * math.pi
    if units == {"radian": 1, "second": -1}:
        return float(root.magnitude)
    raise ModelError(f"{brief(text)} is not a speed: name one angle per time (rad/s, rpm) "
                     "or a frequency (Hz, 1/min)", path)


def unit_expression(unit: str, what: str, path: str, text: str = "") -> str:
    """Check a unit expression against the grammar and spell it for pint.

    Names (letters, µ, °, Ω, inner underscores; at most :data:`MAX_NAME` characters) are
    joined by ``*``, ``·``, ``.``, ``/`` or spaces, the factor ``1`` may stand for a name
    (``1/min``), powers are whole numbers up to :data:`MAX_POWER` in magnitude (``^2``,
    ``**-1``, ``^(-1)``), parentheses nest at most :data:`MAX_PARENS` deep.

    >>> unit_expression("N·m", "torque", "x"), unit_expression("/min", "speed", "x")
    ('N*m', '1/min')
    >>> unit_expression("rev / min^(-1)", "speed", "x")
    'revolution/min**-1'
    """
    text = text or unit
    tokens, pos, depth, expect_operand = [], 0, 0, True
    if unit.lstrip().startswith("/"):
        tokens, expect_operand = ["1"], False  # "/min" is "1/min"
    while pos < len(unit.rstrip()):
        match = _TOKEN.match(unit, pos)
        if match is None or match.end() == pos:
            raise _refuse(text, what, f"unexpected {unit[pos:].strip()[:10]!r}", path)
        pos, group = match.end(), match.lastgroup
        token = match.group(group)
        if group in ("name", "one") or token == "(":
            if not expect_operand:
                tokens.append("*")           # "N m": product by juxtaposition
            if group == "name" and len(token) > MAX_NAME:
                raise _refuse(text, what, f"a unit name longer than {MAX_NAME} characters",
                              path)
            depth += token == "("
            if depth > MAX_PARENS:
                raise _refuse(text, what, f"parentheses deeper than {MAX_PARENS}", path)
            tokens.append(_ALIASES.get(token, token))
            expect_operand = token == "("
        elif expect_operand:
            raise _refuse(text, what, f"{token!r} needs a unit before it", path)
        elif group == "pow":
            power = int(match.group("power") or match.group("inner"))
            if abs(power) > MAX_POWER:
                raise _refuse(text, what, "a unit's power must be a whole number from "
                              f"-{MAX_POWER} to {MAX_POWER}", path)
            tokens.append(f"**{power}")
        elif token == ")":
            depth -= 1
            if depth < 0:
                raise _refuse(text, what, "unbalanced parentheses", path)
            tokens.append(")")
        else:
            tokens.append("/" if token == "/" else "*")
            expect_operand = True
    if expect_operand or depth:
        raise _refuse(text, what, "the unit is incomplete", path)
    return "".join(tokens)


def bare_speed_caveat(value: object, path: str) -> Caveat | None:
    """The caveat for a port speed written without a unit (read as rad/s), else None.

    >>> print(bare_speed_caveat(1500, "ports[0].speed"))
    ports[0].speed: no unit: read as 1500 rad/s (14,324 rpm); write '1500 rad/s' to keep \
it, or '1500 rpm'
    >>> bare_speed_caveat("1500 rpm", "ports[0].speed") is None
    True
    """
    if isinstance(value, bool):
        return None
    if isinstance(value, str):
        match = _NUMBER_UNIT.fullmatch(value)
        if match is None or match.group(2):
            return None
        shown = match.group(1)
    elif isinstance(value, (int, float)):
        shown = repr(value)
    else:
        return None
    speed = float(shown)
    if speed == 0 or not math.isfinite(speed):
        return None  # zero is zero in every unit
    rpm = speed / _RPM
    rpm_text = f"{rpm:,.0f}" if abs(rpm) >= 100 else f"{rpm:.3g}"
    return Caveat(f"no unit: read as {shown} rad/s ({rpm_text} rpm); write '{shown} rad/s' "
                  f"to keep it, or '{shown} rpm'", path, "bare-speed")


def _split(text: str, what: str, path: str) -> tuple[float, str]:
    """(number, unit text) of a quantity string, refusing what the grammar does not read."""
    if len(text) > MAX_TEXT:
        raise _refuse(text, what, f"longer than {MAX_TEXT} characters", path)
    match = _NUMBER_UNIT.fullmatch(text)
    if match is None:
        raise _refuse(text, what, "expected a number, then a unit (like '1500 rpm')", path)
    return float(match.group(1)), match.group(2)


def _parse_string(text: str, kind: str, path: str) -> float:
    number, unit = _split(text, kind, path)
    return _si(number, unit, kind, text, path) if unit else number


def _si(number: float, unit: str, kind: str, text: str, path: str) -> float:
    """``number unit`` in the SI unit of ``kind``: the table, else pint."""
    if kind == "speed":
        return speed_in_rad_s(number, unit, text, path)
    factor, spelled = _lookup(unit, kind, kind, text, path)
    if factor is not None:
        return number * factor
    return _convert(number, spelled, SI_UNITS[kind], text, kind, path)


def _lookup(unit: str, table: str, what: str, text: str,
            path: str) -> tuple[float | None, str]:
    """(factor or None, the unit spelled for pint): ``unit`` in ``_TABLES[table]`` as
    written, else in any case if that names one unit there; two units differing only in
    case (mW, MW) are an error naming both."""
    expression = unit_expression(unit, what, path, text)
    exact, folded = _index(table)
    if expression in exact:
        return exact[expression], expression
    found = folded.get(unit_expression(unit.lower(), what, path, text).lower(), {})
    if len(found) > 1:
        raise _refuse(text, what, f"{unit.strip()!r} could be {' or '.join(found.values())}; "
                      "write the unit with its exact case", path)
    return next(iter(found), None), expression


@lru_cache(maxsize=None)
def _index(table: str) -> tuple[dict[str, float], dict[str, dict[float, str]]]:
    """``_TABLES[table]`` by the grammar's spelling, and by its lower case (with the
    units, by factor, that share it)."""
    exact: dict[str, float] = {}
    folded: dict[str, dict[float, str]] = {}
    for spellings, factor in _TABLES[table]:
        for spelling in spellings:
            exact[unit_expression(spelling, table, "")] = factor
            key = unit_expression(spelling.lower(), table, "").lower()
            folded.setdefault(key, {})[factor] = spellings[0]
    return exact, folded


def _convert(number: float, expression: str, target: str, text: str, what: str,
             path: str) -> float:
    """``number expression`` (checked by the grammar) in ``target`` units, by pint."""
    quantity = _pint_quantity(number, expression, text, what, path)
    try:
        return float(quantity.to(target).magnitude)
    except _pint().errors.DimensionalityError:
        raise ModelError(f"{brief(text)} is not a {what}: {accepted_units(what)}",
                         path) from None


def _pint_quantity(number: float, expression: str, text: str, what: str, path: str):
    pint = _pint()
    try:
        return _registry().Quantity(number, expression)
    except (pint.errors.UndefinedUnitError, pint.errors.DefinitionSyntaxError) as exc:
        names = ", ".join(repr(n) for n in getattr(exc, "unit_names", ())) or "a unit"
        raise ModelError(f"unknown unit {names} in {brief(text)}: {accepted_units(what)}",
                         path) from None
    except Exception as exc:  # pint raises assorted errors for text it cannot read
        raise _refuse(text, what, str(exc), path) from None


def _refuse(text: str, what: str, reason: str, path: str) -> ModelError:
    return ModelError(f"cannot read {brief(text)} as a {what}: {reason}", path)


def _pint():
    import pint

    return pint


@lru_cache(maxsize=1)
def _registry():
    import pint

    try:  # pint's on-disk cache of parsed definitions roughly halves the start-up
        registry = pint.UnitRegistry(cache_folder=":auto:")
    except Exception:  # pragma: no cover - unwritable cache folder
        registry = pint.UnitRegistry()
    return registry
