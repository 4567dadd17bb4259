"""Arc-minutes as degrees-minutes-seconds text, the way the paper prints them."""
from __future__ import annotations

import math


def format_arcmin(value: float, decimals: int = 1) -> str:
    """``6.34`` → ``6'20.4"`` (minutes and seconds; ASCII primes).

    >>> format_arcmin(6.34), format_arcmin(2.0583), format_arcmin(-0.5)
    ('6\\'20.4"', '2\\'3.5"', '-0\\'30.0"')
    """
    if not math.isfinite(value):
        return str(value)
    sign = "-" if value < 0 else ""
    seconds = round(abs(value) * 60.0, decimals)
    minutes, rest = divmod(seconds, 60.0)
    return f"{sign}{int(minutes)}'{rest:.{decimals}f}\""
