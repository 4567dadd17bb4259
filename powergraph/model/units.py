"""Physical quantities in model files: plain SI numbers or strings with units.

A handful of everyday units (rpm, rad/s, W, kW, N*m, ...) are converted from a small
table so that `powergraph solve` does not pay pint's start-up time; anything else is
handed to pint, which stays the authority (the test-suite checks the table against it).

Examples
--------
>>> parse_quantity("1500 rpm", "speed", "ports[0].speed")
157.07963267948966
>>> parse_quantity("2.27 kW", "power", "ports[0].power")
2270.0
>>> parse_quantity(12.5, "torque", "ports[1].torque")
12.5
"""
from __future__ import annotations

import math
import re
from functools import lru_cache

from powergraph.errors import ModelError
from powergraph.model.yaml_loader import brief
from powergraph.units_si import RAD_S_PER_RPM

#: SI unit of each kind of quantity a model may carry.
SI_UNITS = {"speed": "rad/s", "power": "W", "torque": "N*m", "length": "mm"}

# Factor to the SI unit of the kind (mm for lengths, as the geometry tables use).
_FAST = {
    "speed": {"rad/s": 1.0, "rpm": RAD_S_PER_RPM, "rev/min": RAD_S_PER_RPM,
              "1/s": 1.0, "rad/min": 1 / 60, "deg/s": math.pi / 180, "rps": 2 * math.pi,
              "rev/s": 2 * math.pi},
    "power": {},  # case matters (mW vs MW): see _CASE_SENSITIVE_POWER
    "torque": {"n*m": 1.0, "n m": 1.0, "nm": 1.0, "n·m": 1.0, "n.m": 1.0, "kn*m": 1e3,
               "n*mm": 1e-3, "nmm": 1e-3},
    "length": {"mm": 1.0, "m": 1e3, "cm": 10.0, "um": 1e-3, "µm": 1e-3},
}
_CASE_SENSITIVE_POWER = {"W": 1.0, "kW": 1e3, "MW": 1e6, "mW": 1e-3}
_NUMBER_UNIT = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$")


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
        Unknown unit, wrong dimension, or not a number.

    Examples
    --------
    >>> round(parse_quantity("120 N*m", "torque", "x"), 9)
    120.0
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


def _parse_string(text: str, kind: str, path: str) -> float:
    match = _NUMBER_UNIT.match(text)
    if match:
        number, unit = float(match.group(1)), match.group(2)
        if unit == "":
            return number
        if kind == "power" and unit in _CASE_SENSITIVE_POWER:
            return number * _CASE_SENSITIVE_POWER[unit]
        factor = _FAST[kind].get(unit.lower()) if kind != "power" else None
        if factor is not None:
            return number * factor
    return _parse_with_pint(text, kind, path)


def _parse_with_pint(text: str, kind: str, path: str) -> float:
    registry = _registry()
    import pint

    try:
        quantity = registry.Quantity(text)
    except (pint.errors.UndefinedUnitError, pint.errors.DefinitionSyntaxError) as exc:
        raise ModelError(f"unknown unit in {brief(text)} ({exc})", path) from None
    except Exception as exc:  # pint raises assorted errors for unparsable text
        raise ModelError(f"cannot read {brief(text)} as a {kind}: {exc}", path) from None
    try:
        return float(quantity.to(SI_UNITS[kind]).magnitude)
    except pint.errors.DimensionalityError:
        raise ModelError(
            f"{brief(text)} is not a {kind} (expected units like {SI_UNITS[kind]})", path
        ) from None


@lru_cache(maxsize=1)
def _registry():
    import pint

    try:  # pint's on-disk cache of parsed definitions roughly halves the start-up
        registry = pint.UnitRegistry(cache_folder=":auto:")
    except Exception:  # pragma: no cover - unwritable cache folder
        registry = pint.UnitRegistry()
    return registry
