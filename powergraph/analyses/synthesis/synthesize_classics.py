"""The classic planetary trains as :class:`TrainGraph` s (the synthesis's reference set).

Link 0 is the link the main-axis bearings hang on (a ring in most); any coaxial link may be
chosen as the frame when a train is built. The stepped-planet 2K-H is the 2K-H graph with
a two-step planet layout (:mod:`powergraph.analyses.synthesis.teeth`), not a graph of its own.

Examples
--------
>>> {name: g.dof for name, g in CLASSICS.items()}["RV (2K-H + K-H-V)"]
1
>>> sorted(g.links for g in CLASSICS.values())
[4, 4, 5, 5, 5, 6, 6, 6]
"""
from __future__ import annotations

from powergraph.analyses.synthesis.graph import TrainGraph

#: name -> graph; axis 0 is the main axis throughout.
CLASSICS: dict[str, TrainGraph] = {
    # ring 0, sun 1, planet 2 on carrier 3
    "2K-H": TrainGraph(4, ((0, 1, 0), (0, 3, 0), (3, 2, 1)), ((1, 2, 3), (2, 0, 3)),
                       name="2K-H"),
    # ring 0, sun 1, inner planet 2 and outer planet 3 on carrier 4
    "double planet": TrainGraph(5, ((0, 1, 0), (0, 4, 0), (4, 2, 1), (4, 3, 2)),
                                ((1, 2, 4), (2, 3, 4), (3, 0, 4)), name="double planet"),
    # fixed ring 0, sun 1, output ring 2, carrier 3, planet 4 meshing all three
    "Wolfrom 3K": TrainGraph(5, ((0, 1, 0), (0, 2, 0), (0, 3, 0), (3, 4, 1)),
                             ((1, 4, 3), (4, 0, 3), (4, 2, 3)), name="Wolfrom 3K"),
    # small sun 0, large sun 1, ring 2, carrier 3, short planet 4, long planet 5
    "Ravigneaux": TrainGraph(6, ((0, 1, 0), (0, 2, 0), (0, 3, 0), (3, 4, 1), (3, 5, 2)),
                             ((0, 4, 3), (4, 5, 3), (5, 1, 3), (5, 2, 3)), name="Ravigneaux"),
    # rear carrier 0, common sun 1, front planet 2, front ring 3, front carrier + rear
    # ring 4, rear planet 5
    "Simpson": TrainGraph(6, ((0, 1, 0), (0, 3, 0), (0, 4, 0), (4, 2, 1), (0, 5, 2)),
                          ((1, 2, 4), (2, 3, 4), (1, 5, 0), (5, 4, 0)), name="Simpson"),
    # common ring 0, sun 1, planet 2 on carrier 3 = second sun, planet 4 on carrier 5
    "two 2K-H stages": TrainGraph(6, ((0, 1, 0), (0, 3, 0), (0, 5, 0), (3, 2, 1), (5, 4, 2)),
                                  ((1, 2, 3), (2, 0, 3), (3, 4, 5), (4, 0, 5)),
                                  name="two 2K-H stages"),
    # ring 0, eccentric crank 1, planet (cycloid disc) 2, output 3 coupled to the planet
    "K-H-V": TrainGraph(4, ((0, 1, 0), (0, 3, 0), (1, 2, 1)), ((2, 0, 1),),
                        name="K-H-V", couplings=((2, 3),)),
    # pin ring 0, centre gear 1, crank with its planet gear 2 on the planet frame 3 (the
    # output), cycloid disc 4 on the crank's eccentric, coupled to the planet frame
    "RV (2K-H + K-H-V)": TrainGraph(5, ((0, 1, 0), (0, 3, 0), (3, 2, 1), (2, 4, 2)),
                                    ((1, 2, 3), (4, 0, 2)), name="RV (2K-H + K-H-V)",
                                    couplings=((4, 3),)),
}


def classic_graphs(max_links: int = 6) -> tuple[TrainGraph, ...]:
    """The classic graphs with at most ``max_links`` links, in :data:`CLASSICS` order.

    >>> [g.name for g in classic_graphs(4)]
    ['2K-H', 'K-H-V']
    """
    return tuple(g for g in CLASSICS.values() if g.links <= max_links)
