"""A mesh's ``cycloid:`` block (Csobán 2021).

A cycloid-disc / pin-ring mesh may carry the data of its ratio-fluctuation analysis
(:mod:`powergraph.analyses.cycloid`)::

    links:
      - type: mesh
        between: [4, 5]            # cycloid disc (z1 teeth), pin ring (internal, z1 + 1 pins)
        carrier: 3                 # the crank
        cycloid:
          module: 1                # mm: pin circle radius m·z2/2, pin radius rc·m
          profile_error: 0.0045    # d, mm: the disc profile moved inward along its normal
          shift: 0.3               # x, 0 < x < 1: eccentricity (1 − x)·m/2 (default 0.3)
          rc: 1                    # pin-radius factor (default 1)

Lengths are numbers in mm or strings with a length unit (``"4.5 um"``). The mesh must be a
cycloid pair: one external gear (the disc, ``teeth`` z1 ≥ 3) and one internal gear (the pin
ring) with exactly one more tooth. Types and ranges are checked against the model schema
(:mod:`powergraph.model.schema`); this module checks the pair. Undercut of the profile is
checked by the analysis.

Examples
--------
>>> from powergraph.model import model_from_dict
>>> m = model_from_dict({"name": "cycloid stage",
...     "components": {0: {"role": "frame"}, 1: {}, 4: {"teeth": 39},
...                    5: {"teeth": 40, "internal": True}},
...     "links": [{"type": "mesh", "between": [4, 5], "carrier": 1,
...                "cycloid": {"module": 1, "profile_error": 0.0045}},
...               {"type": "fixed", "between": [5, 0]}],
...     "ports": [{"component": 1, "role": "input"}, {"component": 4, "role": "output"}]})
>>> block = m.links[0].blocks["cycloid"]
>>> block.disc, block.teeth, block.profile_error, block.shift, block.rc
('4', 39, 0.0045, 0.3, 1.0)
"""
from __future__ import annotations

from typing import Any, Mapping

from powergraph.errors import ModelError
from powergraph.model.units import parse_quantity
from powergraph.records import record


@record
class CycloidBlock:
    """A validated ``cycloid:`` block (lengths in mm).

    ``disc`` and ``ring`` are the ids of the cycloid disc (``teeth`` z1) and the pin ring.
    """

    module: float
    profile_error: float
    disc: str
    ring: str
    teeth: int
    shift: float = 0.3
    rc: float = 1.0

    def to_dict(self) -> dict:
        return {"module": self.module, "profile_error": self.profile_error,
                "shift": self.shift, "rc": self.rc}


def validate_cycloid(raw: Any, path: str, pair: tuple, components: Mapping) -> CycloidBlock:
    """Validate a mesh's ``cycloid`` block.

    Parameters
    ----------
    raw : Any
        The block as written in the file.
    path : str
        Its place in the file (``links[1].cycloid``).
    pair : tuple of str
        The mesh's two gear ids.
    components : mapping
        ``{id: Component}`` of the model.

    Returns
    -------
    CycloidBlock

    Raises
    ------
    ModelError
        Unknown or missing keys, non-numbers, impossible values (checked against the
        schema), or a mesh that is not a cycloid pair, with the place
        (``links[1].cycloid.shift``).
    """
    from powergraph.model.conform import conform, definition

    conform(raw, definition("cycloid"), path)
    disc, ring = _roles(pair, components, path)
    return CycloidBlock(module=parse_quantity(raw["module"], "length", f"{path}.module"),
                        profile_error=parse_quantity(raw["profile_error"], "length",
                                                     f"{path}.profile_error"),
                        disc=disc, ring=ring, teeth=components[disc].teeth,
                        shift=float(raw.get("shift", 0.3)), rc=float(raw.get("rc", 1.0)))


def _roles(pair: tuple, components: Mapping, path: str) -> tuple[str, str]:
    """(disc id, pin-ring id), or a ModelError if the mesh is not a cycloid pair."""
    internal = [gear for gear in pair if components[gear].internal]
    if len(internal) != 1:
        raise ModelError("a cycloid mesh pairs a disc with a pin ring: exactly one of the "
                         f"two gears must be internal, found {len(internal)}", path)
    ring = internal[0]
    disc = next(gear for gear in pair if gear != ring)
    z1, z2 = components[disc].teeth, components[ring].teeth
    if z1 is None or z2 is None:
        raise ModelError("the disc and the pin ring need teeth for a cycloid block", path)
    if z1 < 3 or z2 != z1 + 1:
        raise ModelError(f"a cycloid stage needs a disc of z1 >= 3 teeth and z1 + 1 pins; "
                         f"got disc {disc!r} with {z1} and ring {ring!r} with {z2}", path)
    return disc, ring
