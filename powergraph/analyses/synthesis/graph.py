"""The graph of a planetary gear train, as the structural-synthesis literature draws it.

Vertices are the train's links (rigid members, the frame among them). Two kinds of edge:

- a **turning pair** ``(u, v, axis)``: ``u`` and ``v`` turn relative to each other about
  the axis labelled ``axis`` (an integer; two turning pairs with the same label share the
  geometric axis, which is what "level" means in the literature);
- a **gear pair** ``(u, v, carrier)``: ``u`` and ``v`` mesh, and ``carrier`` (the transfer
  vertex) is the link on which both of their axes are held: ``u`` turns about one axis
  of the carrier and ``v`` about another (directly on the carrier, or through other links
  on the same axis, since the turning pairs of one axis may be arranged in several ways;
  see docs/synthesis.md).

The turning pairs form a spanning tree of the links, so a train of ``N`` links has
``N - 1`` of them, and planar mobility gives ``dof = N - 1 - G`` for ``G`` gear pairs.

Optionally, **couplings** ``(u, v)``: an equal-speed mechanism (parallel cranks, pin-and-hole
"W" mechanism, Oldham coupling) between a planet and a coaxial link, as in the V of a
K-H-V (cycloid) stage; each removes one degree of freedom like a gear pair.
"""
from __future__ import annotations

from typing import Any, Mapping

from powergraph.records import record


@record
class TrainGraph:
    """A planetary gear train as a graph (see the module docstring).

    Examples
    --------
    A sun (1) and a carrier (3) turning on the frame (0), a planet (2) on the carrier:

    >>> sun_and_planet = TrainGraph(links=4,
    ...     turning_pairs=((0, 1, 0), (0, 3, 0), (3, 2, 1)), gear_pairs=((1, 2, 3),))
    >>> sun_and_planet.dof
    2
    """

    links: int
    turning_pairs: tuple[tuple[int, int, int], ...]
    gear_pairs: tuple[tuple[int, int, int], ...]
    name: str | None = None
    couplings: tuple[tuple[int, int], ...] = ()

    @property
    def dof(self) -> int:
        """Degrees of freedom by planar mobility: ``N - 1 - G - C`` (``C`` couplings)."""
        return self.links - 1 - len(self.gear_pairs) - len(self.couplings)

    def axes_of(self, link: int) -> frozenset[int]:
        """The axis labels of the turning pairs at ``link``."""
        return frozenset(axis for u, v, axis in self.turning_pairs if link in (u, v))

    def to_model_dict(self, *, frame: int, inputs: tuple[int, ...], outputs: tuple[int, ...],
                      teeth: Mapping[tuple[int, int], int], internal: Mapping[int, int] = {},
                      mesh_efficiency: float = 1.0, name: str | None = None,
                      names: Mapping[str, str] = {}, counts: Mapping[str, int] = {},
                      input_power: float = 1000.0, input_speed: float = 100.0) -> dict[str, Any]:
        """A powergraph model document (as :func:`powergraph.model.model_from_dict` takes).

        Link ``L`` becomes component ``"L{L}"``; side ``s`` (0 or 1) of gear pair ``k``
        becomes gear ``"g{k}{'ab'[s]}"`` fixed to its link, with ``teeth[(k, s)]`` teeth;
        ``internal[k] = s`` makes side ``s`` of pair ``k`` the internal gear (a ring).
        Turning pairs are recorded as ``bearing`` links, couplings as ``coupling`` links.

        Parameters
        ----------
        frame, inputs, outputs : link numbers of the housing, the input(s) and output(s)
        teeth : ``{(pair, side): teeth}`` for every side of every gear pair
        internal : ``{pair: side}`` for internal pairs
        mesh_efficiency : the basic efficiency of every mesh
        names, counts : ``name`` and ``count`` (identical planets) of components, by id

        Examples
        --------
        >>> g = TrainGraph(3, ((0, 1, 0), (0, 2, 1)), ((1, 2, 0),))
        >>> doc = g.to_model_dict(frame=0, inputs=(1,), outputs=(2,), teeth={(0, 0): 20, (0, 1): 40})
        >>> doc["links"][0]
        {'type': 'mesh', 'between': ['g0a', 'g0b'], 'carrier': 'L0'}
        """
        components: dict[str, dict[str, Any]] = {
            f"L{n}": ({"role": "frame"} if n == frame else {}) for n in range(self.links)}
        meshes, fixed = [], []
        for k, (u, v, carrier) in enumerate(self.gear_pairs):
            for side, link in enumerate((u, v)):
                gear = f"g{k}{'ab'[side]}"
                components[gear] = {"teeth": int(teeth[(k, side)])}
                if internal.get(k) == side:
                    components[gear]["internal"] = True
                fixed.append({"type": "fixed", "between": [gear, f"L{link}"]})
            meshes.append({"type": "mesh", "between": [f"g{k}a", f"g{k}b"],
                           "carrier": f"L{carrier}"})
        bearings = [{"type": "bearing", "between": [f"L{u}", f"L{v}"]}
                    for u, v, _ in self.turning_pairs]
        couplings = [{"type": "coupling", "between": [f"L{u}", f"L{v}"]}
                     for u, v in self.couplings]
        for cid, text in names.items():
            components[cid] = {"name": text, **components[cid]}
        for cid, count in counts.items():
            if count > 1:
                components[cid]["count"] = int(count)
        ports = [{"component": f"L{n}", "role": "input", "speed": f"{input_speed!r} rad/s",
                  **({"power": input_power} if i == 0 else {})} for i, n in enumerate(inputs)]
        ports += [{"component": f"L{n}", "role": "output"} for n in outputs]
        return {"name": name or self.name or f"{self.links}-link train",
                "defaults": {"mesh_efficiency": mesh_efficiency},
                "components": components, "links": meshes + fixed + couplings + bearings, "ports": ports}
