"""Isomorphism of train graphs: the two graphs compared, the matcher, a canonical form.

Two levels (Yang & Ding 2018, "New graph representation for planetary gear trains"):

- the **rotation graph** (r-graph) says which links mesh and which link carries each mesh:
  here a vertex per link and a vertex per gear pair, the gear-pair vertex joined to its two
  gears (``gear`` edges) and to its carrier (``carrier`` edge);
- the **displacement graph** (d-graph) adds the levels: which links turn about a common
  axis. Here each axis is a vertex joined to the links that turn about it (``turn``
  edges), and gear pairs are ``gear`` edges between links (the carrier follows from the
  axes).

Axis labels and link numbers are names only, so they never enter the comparison: vertices
match on their kind, edges on theirs (:func:`node_match`, :func:`edge_match`). A
Weisfeiler-Lehman hash sorts graphs into buckets first; ``networkx``'s VF2 decides within
a bucket (:func:`classify`). Axis structures are trees: :func:`structure_code` and
:func:`automorphisms` use their centre-rooted canonical codes instead.
:func:`canonical_form` is an exact certificate for any of these graphs, equal for two
graphs exactly when they are isomorphic (slow; for tests and spot checks).
"""
from __future__ import annotations

from itertools import permutations, product
from typing import Any, Callable, Iterable, Sequence, TypeVar

T = TypeVar("T")


def node_match(a: dict, b: dict) -> bool:
    """Vertices match when they are of the same kind (link, axis, gear pair)."""
    return a["kind"] == b["kind"]


def edge_match(a: dict, b: dict) -> bool:
    """Edges match when they are of the same kind (turn, gear, carrier)."""
    return a["kind"] == b["kind"]


def incidence_graph(links: int, axes: Sequence[Iterable[int]]) -> Any:
    """Links and axes, each axis joined to the links that turn about it.

    Examples
    --------
    >>> g = incidence_graph(3, [{0, 1}, {0, 2}])
    >>> g.number_of_nodes(), g.number_of_edges()
    (5, 4)
    """
    import networkx as nx

    graph = nx.Graph()
    graph.add_nodes_from(((0, n) for n in range(links)), kind="link")
    for a, axis in enumerate(axes):
        graph.add_node((1, a), kind="axis")
        graph.add_edges_from((((0, n), (1, a)) for n in axis), kind="turn")
    return graph


def displacement_graph(links: int, axes: Sequence[Iterable[int]],
                       gear_pairs: Iterable[Sequence[int]]) -> Any:
    """The d-graph: :func:`incidence_graph` plus a ``gear`` edge per gear pair.

    Examples
    --------
    >>> displacement_graph(3, [{0, 1}, {0, 2}], [(1, 2, 0)]).number_of_edges()
    5
    """
    graph = incidence_graph(links, axes)
    graph.add_edges_from((((0, u), (0, v)) for u, v, *_ in gear_pairs), kind="gear")
    return graph


def rotation_graph(links: int, gear_pairs: Iterable[Sequence[int]]) -> Any:
    """The r-graph: links and gear pairs, each pair joined to its gears and its carrier.

    Examples
    --------
    >>> rotation_graph(3, [(1, 2, 0)]).number_of_edges()
    3
    """
    import networkx as nx

    graph = nx.Graph()
    graph.add_nodes_from(((0, n) for n in range(links)), kind="link")
    for k, (u, v, carrier) in enumerate(gear_pairs):
        graph.add_node((2, k), kind="mesh")
        graph.add_edges_from((((2, k), (0, u)), ((2, k), (0, v))), kind="gear")
        graph.add_edge((2, k), (0, carrier), kind="carrier")
    return graph


def wl_hash(graph: Any) -> str:
    """Weisfeiler-Lehman hash on vertex and edge kinds (equal for isomorphic graphs)."""
    import networkx as nx

    return nx.weisfeiler_lehman_graph_hash(graph, node_attr="kind", edge_attr="kind",
                                           iterations=4)


def same(a: Any, b: Any) -> bool:
    """Whether two train graphs (d- or r-graphs) are isomorphic, kinds respected."""
    import networkx as nx

    return nx.is_isomorphic(a, b, node_match=node_match, edge_match=edge_match)


def classify(items: Iterable[T], graph_of: Callable[[T], Any]) -> tuple[list[T], list[int]]:
    """One representative per isomorphism class, and the class index of every item.

    Examples
    --------
    >>> reps, index = classify([[(1, 2, 0)], [(2, 1, 0)]], lambda g: rotation_graph(3, g))
    >>> len(reps), index
    (1, [0, 0])
    """
    buckets: dict[str, list[tuple[Any, int]]] = {}
    representatives: list[T] = []
    index: list[int] = []
    for item in items:
        graph = graph_of(item)
        bucket = buckets.setdefault(wl_hash(graph), [])
        for other, k in bucket:
            if same(graph, other):
                index.append(k)
                break
        else:
            bucket.append((graph, len(representatives)))
            index.append(len(representatives))
            representatives.append(item)
    return representatives, index


def automorphisms(links: int, axes: Sequence[Iterable[int]]) -> list[tuple[int, ...]]:
    """The link permutations that map an axis structure onto itself.

    Two gear-pair sets on the same axis structure give isomorphic d-graphs exactly when
    one of these permutations maps one onto the other, since the axis structure is part of
    the d-graph. The structure is a tree (links and axes), so its automorphisms come from
    its centre-rooted canonical codes (Aho, Hopcroft & Ullman): children with equal codes
    are swapped in every way, recursively. (VF2 on the structure matched with itself gives
    the same group, more slowly; the tests compare the two.)

    Examples
    --------
    >>> sorted(automorphisms(3, [{0, 1}, {0, 2}]))
    [(0, 1, 2), (0, 2, 1)]
    """
    graph = incidence_graph(links, list(axes))
    root, codes, parent = _rooted_codes(graph)
    return [tuple(m[(0, n)][1] for n in range(links))
            for m in _maps(graph, codes, parent, root, root)]


def structure_code(links: int, axes: Sequence[Iterable[int]]) -> str:
    """A canonical code of an axis structure: equal exactly for isomorphic structures.

    Examples
    --------
    >>> structure_code(3, [{0, 1}, {0, 2}]) == structure_code(3, [{1, 2}, {2, 0}])
    True
    """
    root, codes, _ = _rooted_codes(incidence_graph(links, list(axes)))
    return codes[root]


def _rooted_codes(tree: Any) -> tuple[Any, dict, dict]:
    """The tree rooted at its centre (a link and an axis never swap, so with two centres
    either one is fixed by every automorphism), each vertex's subtree code, its parent."""
    import networkx as nx

    root = min(nx.center(tree), key=lambda v: tree.nodes[v]["kind"])
    codes: dict[Any, str] = {}
    parent = {root: None}
    order = list(nx.dfs_preorder_nodes(tree, root))
    for v in order:
        for w in tree[v]:
            if w != parent[v]:
                parent[w] = v
    for v in reversed(order):
        inner = sorted(codes[w] for w in tree[v] if w != parent[v])
        codes[v] = tree.nodes[v]["kind"][0] + "(" + "".join(inner) + ")"
    return root, codes, parent


def _maps(tree: Any, codes: dict, parent: dict, v: Any, w: Any) -> Iterable[dict]:
    """Every isomorphism of the subtree at ``v`` onto the subtree at ``w`` (equal codes)."""
    mine = [c for c in tree[v] if c != parent[v]]
    theirs = [c for c in tree[w] if c != parent[w]]
    groups: dict[str, tuple[list, list]] = {}
    for c in mine:
        groups.setdefault(codes[c], ([], []))[0].append(c)
    for c in theirs:
        groups[codes[c]][1].append(c)
    options = []
    for source, target in groups.values():
        options.append([list(zip(source, perm)) for perm in permutations(target)])
    for pairing in product(*options):
        pairs = [pair for group in pairing for pair in group]
        for parts in product(*(list(_maps(tree, codes, parent, a, b)) for a, b in pairs)):
            merged = {v: w}
            for part in parts:
                merged.update(part)
            yield merged


def images(gear_pairs: Iterable[Sequence[int]], group: Sequence[Sequence[int]]) -> set[tuple]:
    """Every image of a gear-pair set under a group of link permutations (sorted tuples).

    Examples
    --------
    >>> sorted(images([(1, 2, 0)], [(0, 1, 2), (1, 0, 2)]))
    [((0, 2, 1),), ((1, 2, 0),)]
    """
    pairs = list(gear_pairs)
    return {tuple(sorted((min(p[u], p[v]), max(p[u], p[v]), p[c]) for u, v, c in pairs))
            for p in group}


def unique(items: Iterable[T], graph_of: Callable[[T], Any]) -> list[T]:
    """One item per isomorphism class of ``graph_of(item)``, in the order first seen."""
    return classify(items, graph_of)[0]


def canonical_form(graph: Any) -> str:
    """A string equal for two graphs exactly when they are isomorphic (kinds respected).

    Vertices are coloured by their Weisfeiler-Lehman subtree hashes (an invariant colour),
    classes are ordered by colour, and the smallest edge list over the orderings within
    each class is the form: exact, and quick on train graphs whose colour classes are small.

    Examples
    --------
    >>> canonical_form(rotation_graph(3, [(1, 2, 0)])) == \\
    ...     canonical_form(rotation_graph(3, [(0, 2, 1)]))
    True
    """
    import networkx as nx

    depth = graph.number_of_nodes()
    hashes = nx.weisfeiler_lehman_subgraph_hashes(graph, node_attr="kind", edge_attr="kind",
                                                  iterations=max(1, depth))
    colour = {v: graph.nodes[v]["kind"] + ":" + h[-1] for v, h in hashes.items()}
    classes: dict[str, list[Any]] = {}
    for v in graph.nodes:
        classes.setdefault(colour[v], []).append(v)
    order = sorted(classes)
    best = None
    for choice in product(*(permutations(classes[c]) for c in order)):
        number = {v: i for i, v in enumerate(v for block in choice for v in block)}
        edges = sorted((min(number[a], number[b]), max(number[a], number[b]), d["kind"])
                       for a, b, d in graph.edges(data=True))
        if best is None or edges < best:
            best = edges
    kinds = [graph.nodes[v]["kind"] for block in (classes[c] for c in order) for v in block]
    return repr((order, kinds, best))
