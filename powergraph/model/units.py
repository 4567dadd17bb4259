"""Physical quantities in model files: plain SI numbers or strings with units.

A quantity string is read with a small grammar of our own before any unit library sees
it (:func:`unit_expression`): a decimal number, then unit names joined by ``*``, ``/``,
``·`` or spaces, with small integer powers (``^2``, ``**-1``) and shallow parentheses, in
at most :data:`MAX_TEXT` characters. Anything else is refused at once, so a hostile string
(``9**9**9 W``, a unit with hundreds of prefixes) cannot keep pint busy.

A handful of everyday units (rpm, rad/s, Hz, W, kW, N*m, ...) are converted from a small
table so that `powergraph solve` does not pay pint's start-up time; anything else is
handed to pint (the test-suite checks the table against it).

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
SI_UNITS = {"speed": "rad/s", "power": "W", "torque": "N*m", "length": "mm"}
#: Longest quantity string read, and longest unit name in it.
MAX_TEXT, MAX_NAME = 64, 24
#: Largest power of a unit (``m^4``) and deepest parentheses in a quantity string.
MAX_POWER, MAX_PARENS = 4, 2

_RPM = RAD_S_PER_RPM
# Factor to the SI unit of the kind (mm for lengths, as the geometry tables use). The
# speeds obey speed_in_rad_s's rule: a pure frequency (Hz, 1/min) is revolutions per time.
_FAST = {
    "speed": {"rad/s": 1.0, "rpm": _RPM, "rev/min": _RPM, "r/min": _RPM, "1/min": _RPM,
              "/min": _RPM, "min^-1": _RPM, "hz": 2 * math.pi, "1/s": 2 * math.pi,
              "s^-1": 2 * math.pi, "rad/min": 1 / 60, "deg/s": math.pi / 180,
              "rps": 2 * math.pi, "rev/s": 2 * math.pi},
    "power": {},  # case matters (mW vs MW): see _CASE_SENSITIVE_POWER
    "torque": {"n*m": 1.0, "n m": 1.0, "nm": 1.0, "n·m": 1.0, "n.m": 1.0, "kn*m": 1e3,
               "n*mm": 1e-3, "nmm": 1e-3},
    "length": {"mm": 1.0, "m": 1e3, "cm": 10.0, "um": 1e-3, "µm": 1e-3},
}
_CASE_SENSITIVE_POWER = {"W": 1.0, "kW": 1e3, "MW": 1e6, "mW": 1e-3}
# Common spellings converted without pint, by target unit (case matters: mPa vs MPa).
_FAST_IN = {"mPa*s": {"mPa*s": 1.0, "mPa s": 1.0, "mPa·s": 1.0, "mPa.s": 1.0, "cP": 1.0,
                      "Pa*s": 1e3, "Pa s": 1e3, "Pa·s": 1e3, "Pa.s": 1e3}}
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
    number, expression = _split(text, what, path)
    factor = _FAST_IN.get(unit, {}).get(expression)
    if factor is not None:
        return number * factor
    return _convert(number, expression, unit, text, what, path) if expression else number


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
    factor = _FAST["speed"].get(unit.strip().lower())
    if factor is not None:
        return number * factor
    text = text or f"{number:g} {unit}"
    quantity = _pint_quantity(number, unit_expression(unit, "speed", path), text, "speed",
                              path)
    if quantity.dimensionality != _registry().parse_units("Hz").dimensionality:
        raise ModelError(f"{brief(text)} is not a speed (expected units like rad/s, rpm or "
                         "Hz)", path)
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
    if unit == "":
        return number
    if kind == "speed":
        return speed_in_rad_s(number, unit, text, path)
    if kind == "power" and unit in _CASE_SENSITIVE_POWER:
        return number * _CASE_SENSITIVE_POWER[unit]
    factor = _FAST[kind].get(unit.lower()) if kind != "power" else None
    if factor is not None:
        return number * factor
    return _convert(number, unit, SI_UNITS[kind], text, kind, path)


def _convert(number: float, unit: str, target: str, text: str, what: str,
             path: str) -> float:
    """``number unit`` in ``target`` units, through the grammar and pint."""
    quantity = _pint_quantity(number, unit_expression(unit, what, path, text), text, what,
                              path)
    try:
        return float(quantity.to(target).magnitude)
    except _pint().errors.DimensionalityError:
        raise ModelError(f"{brief(text)} is not a {what} (expected units like {target})",
                         path) from None


def _pint_quantity(number: float, expression: str, text: str, what: str, path: str):
    pint = _pint()
    try:
        return _registry().Quantity(number, expression)
    except (pint.errors.UndefinedUnitError, pint.errors.DefinitionSyntaxError) as exc:
        raise ModelError(f"unknown unit in {brief(text)} ({exc})", path) from None
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
