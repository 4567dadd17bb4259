"""Synthesis for a ratio (powergraph.analyses.synthesis.synthesize, teeth, rank) and the
Dask map (powergraph.analyses.parallel).

Expected values: single solves of each listed train (``powergraph.solve`` with
``assert_conservation``), the textbook closed forms of the 2K-H set (Willis: with the ring
fixed, sun to carrier ``1 + z_r/z_s``, …), the RV reducer's ``1 + z_2 z_5 / (z_1 (z_5 - z_4))``,
the planet assembly conditions as textbooks state them (simple planets ``(z_s + z_r)/n``
whole; stepped planets ``(z_s z_p2 + z_r z_p1)/(n gcd(z_p1, z_p2))`` whole; double planets
``(z_r - z_s)/n`` whole) and an independent brute-force check of assembly written here.
"""
from __future__ import annotations

import functools
import json
import math
from collections import Counter
from fractions import Fraction

import numpy as np
import pytest

import powergraph as pg
from powergraph.analyses.parallel import map_chunks, scheduler_address
from powergraph.analyses.synthesis import TrainGraph
from powergraph.analyses.synthesis.synthesize import default_graphs, synthesize
from powergraph.analyses.synthesis.synthesize_classics import CLASSICS
from powergraph.analyses.synthesis.teeth import assembles, layouts, neighbours_clear
from powergraph.errors import UsageError
from powergraph.kinematics import backdriven
from powergraph.model import model_from_dict
from powergraph.result import Result
from powergraph.testing import assert_conservation


@functools.lru_cache(maxsize=None)
def graph_named(name: str) -> TrainGraph:
    graphs = {g.name: g for g in (*CLASSICS.values(), *default_graphs(6))}
    return graphs[name]


# --- an independent reading of a row's model: who meshes whom, on which carrier ---------
def geometry(row) -> dict:
    """From the model document alone: for each planet link, its meshes with coaxial gears
    ``(coaxial teeth, planet gear teeth, internal)`` and with other planets."""
    doc = row.model_document()
    gear_link = {link["between"][0]: link["between"][1] for link in doc["links"]
                 if link["type"] == "fixed"}
    teeth = {c: v["teeth"] for c, v in doc["components"].items() if "teeth" in v}
    internal = {c for c, v in doc["components"].items() if v.get("internal")}
    couplings = {x for link in doc["links"] if link["type"] == "coupling"
                 for x in link["between"]}
    carriers = {link["carrier"] for link in doc["links"] if link["type"] == "mesh"}
    meshes = [(link["between"], link["carrier"]) for link in doc["links"]
              if link["type"] == "mesh"]
    # coaxial links turn about the main axis: the axis of the most turning pairs
    graph = graph_named(row.graph)
    count = Counter(axis for *_, axis in graph.turning_pairs)
    main = max(sorted(count), key=lambda axis: count[axis])
    coaxial = {f"L{x}" for u, v, axis in graph.turning_pairs if axis == main for x in (u, v)}
    planets: dict[str, dict] = {}
    for (a, b), carrier in meshes:
        for gear, other in ((a, b), (b, a)):
            link, other_link = gear_link[gear], gear_link[other]
            if link in coaxial:
                continue
            p = planets.setdefault(link, {"coaxial": [], "links": [], "planets": [],
                                          "carrier": carrier, "coupled": link in couplings,
                                          "carries": link in carriers})
            if other_link in coaxial:
                p["coaxial"].append((teeth[other], teeth[gear], other in internal))
                p["links"].append(other_link)
            else:
                p["planets"].append((other_link, teeth[gear], teeth[other]))
    return planets


def check_geometry(row, n: int) -> None:
    """Coaxiality, neighbours and assembly of every replicated planet, checked here."""
    for link, p in geometry(row).items():
        if p["coupled"]:          # the K-H-V disc: one pin more than lobes, a ring
            ((ring, disc, inner),) = p["coaxial"]
            assert inner and ring - disc == 1
            continue
        centres = {zc - zp if inner else zc + zp for zc, zp, inner in p["coaxial"]}
        assert len(centres) == 1, f"{row.name}: planet {link} not coaxial {p}"
        (centre,) = centres
        for _, zp, _ in p["coaxial"]:
            assert zp + 2 < centre * math.sin(math.pi / n), f"{row.name}: planets clash"
        if not p["planets"]:
            assert fits(p["coaxial"], n, phased=p["carries"]), f"{row.name}: no assembly"


def fits(meshes, n: int, phased: bool) -> bool:
    """Brute force: is there a turn ``t`` (in planet-gear teeth fractions) of the planet
    about its axis so that, the carrier turned by 1/n, every coaxial gear is back on its
    teeth: ``z_c/n -+ z_p t`` whole for each mesh (sun: minus, ring: plus)?"""
    if phased:  # the planet carries a crank: every copy identical, t = 0
        return all(Fraction(zc, n).denominator == 1 for zc, _, _ in meshes)
    # t = k / (n L), L = lcm of the planet gears: z_c/n -+ z_p t whole <=> z_c L -+ z_p k = 0 mod nL
    lcm = math.lcm(*[zp for _, zp, _ in meshes])
    k = np.arange(n * lcm)
    ok = np.ones(k.shape, dtype=bool)
    for zc, zp, inner in meshes:
        ok &= (zc * lcm + (zp if inner else -zp) * k) % (n * lcm) == 0
    return bool(ok.any())


def check_single_solve(row) -> None:
    model = model_from_dict(row.model_document())
    forward = pg.solve(model)
    assert_conservation(forward)
    assert forward.ratio == pytest.approx(row.ratio, rel=1e-9)
    assert forward.efficiency == pytest.approx(row.efficiency, rel=1e-9)
    assert forward.circulating_power == pytest.approx(row.circulating_power, rel=1e-9, abs=1e-9)
    back = pg.solve(backdriven(model))
    assert_conservation(back)
    assert back.efficiency == pytest.approx(row.backdrive_efficiency, rel=1e-9)
    largest = max(m.carrier_frame_power for m in forward.meshes)
    assert largest / forward.input_power == pytest.approx(row.max_virtual_power_ratio,
                                                           rel=1e-9)


# --- the whole search at 121 --------------------------------------------------------------
@pytest.fixture(scope="module")
def at_121():
    return synthesize(121, max_links=6, top=None)      # the enumeration's graphs


@pytest.mark.slow
def test_121_lists_an_rv_structure_with_its_closed_form(at_121) -> None:
    rv = [r for r in at_121 if r.graph == "RV (2K-H + K-H-V)"]
    assert rv
    for row in rv:
        planets = geometry(row)
        crank = [p for p in planets.values() if p["carries"] and not p["coupled"]]
        disc = [p for p in planets.values() if p["coupled"]]
        assert len(crank) == 1 and len(disc) == 1      # a 2K-H stage, then a K-H-V stage
        ((z1, z2, ring_1),) = crank[0]["coaxial"]      # centre gear, planet on the crank
        ((z5, z4, ring_2),) = disc[0]["coaxial"]       # pin ring, cycloid disc
        assert not ring_1 and ring_2
        assert row.ratio == pytest.approx(1 + z2 * z5 / (z1 * (z5 - z4)), rel=1e-12)
        assert abs(row.ratio / 121 - 1) <= 0.005


@pytest.mark.slow
def test_121_lists_a_wolfrom_drive(at_121) -> None:
    wolfrom = [r for r in at_121 if r.graph.startswith("Wolfrom 3K")]
    assert wolfrom
    for row in wolfrom:
        ((planet, p),) = geometry(row).items()
        assert len(p["coaxial"]) == 3        # one planet meshing three coaxial gears
        assert row.circulating_power > 0     # Wolfrom drives circulate power
    assert any(sum(inner for *_, inner in p["coaxial"]) == 2      # sun and two rings
               for row in wolfrom for p in geometry(row).values())


@pytest.mark.slow
def test_every_listed_row_is_reproduced_by_a_single_solve(at_121) -> None:
    assert len(at_121) >= 4
    for row in at_121:
        check_single_solve(row)
        assert abs(row.ratio / 121 - 1) <= 0.005
        assert row.meshes == len(row.model_document()["links"]) - len(
            [x for x in row.model_document()["links"] if x["type"] != "mesh"])


@pytest.mark.slow
def test_every_listed_row_is_coaxial_clear_and_assembles(at_121) -> None:
    for row in at_121:
        check_geometry(row, 3)


@pytest.mark.slow
def test_rows_are_ranked_by_efficiency_bands(at_121) -> None:
    eff = [round(r.efficiency, 3) for r in at_121]
    assert eff == sorted(eff, reverse=True)
    assert at_121.feasible >= at_121.arrangements == len(at_121)


# --- the 2K-H in its six arrangements -----------------------------------------------------
def roles(row) -> dict[str, str]:
    """Link of sun, ring and carrier of a 2K-H row, read from its model document."""
    ((_, p),) = geometry(row).items()
    out = {"carrier": p["carrier"]}
    for (_, _, inner), link in zip(p["coaxial"], p["links"]):
        out["ring" if inner else "sun"] = link
    return out


def simple_teeth(row) -> tuple[int, int]:
    """(z_sun, z_ring) of a simple 2K-H row."""
    ((_, p),) = geometry(row).items()
    sun = next(zc for zc, _, inner in p["coaxial"] if not inner)
    ring = next(zc for zc, _, inner in p["coaxial"] if inner)
    return sun, ring


SIX = [  # (ratio, input, output, fixed, closed form in z_s, z_r) — Willis' formula
    (5.0, "sun", "carrier", "ring", lambda s, r: 1 + r / s),
    (0.2, "carrier", "sun", "ring", lambda s, r: 1 / (1 + r / s)),
    (1.25, "ring", "carrier", "sun", lambda s, r: 1 + s / r),
    (0.8, "carrier", "ring", "sun", lambda s, r: 1 / (1 + s / r)),
    (-4.0, "sun", "ring", "carrier", lambda s, r: -r / s),
    (-0.25, "ring", "sun", "carrier", lambda s, r: -s / r),
]


@pytest.mark.parametrize("ratio, inp, out, fixed, closed", SIX)
def test_2kh_found_in_each_of_its_six_arrangements(ratio, inp, out, fixed, closed) -> None:
    result = synthesize(ratio, graphs=[CLASSICS["2K-H"]], top=None)
    simple = [r for r in result if r.layout == "simple"]
    found = [r for r in simple if (roles(r)[inp], roles(r)[out], roles(r)[fixed])
             == (f"L{r.input}", f"L{r.output}", f"L{r.fixed}")]
    assert found, [r.name for r in result]
    for row in found:
        check_single_solve(row)
        check_geometry(row, 3)
        s, r = simple_teeth(row)
        assert row.ratio == pytest.approx(closed(s, r), rel=1e-12)
        assert (s + r) % 3 == 0                          # the textbook assembly condition


def test_double_planet_found_with_its_assembly_condition() -> None:
    # sun in, carrier out, ring fixed: 1 - z_r/z_s, e.g. 36/90: -1.5
    result = synthesize(-1.5, graphs=[CLASSICS["double planet"]], teeth=(12, 60), top=None)
    assert result.rows
    for row in result:
        check_single_solve(row)
        doc = row.model_document()
        zs = [v["teeth"] for c, v in doc["components"].items() if "teeth" in v]
        rings = [v["teeth"] for v in doc["components"].values() if v.get("internal")]
        if len(rings) == 1:                      # the classic form: one sun, one ring
            planets = geometry(row)
            (sun,) = [zc for p in planets.values() for zc, _, inner in p["coaxial"] if not inner]
            assert (rings[0] - sun) % 3 == 0
            assert zs


@pytest.mark.parametrize("name, ratio", [
    pytest.param("Wolfrom 3K", 115.0, marks=pytest.mark.slow),  # models/wolfrom_3k.yaml
    pytest.param("Ravigneaux", 2.4, marks=pytest.mark.slow),    # ravigneaux_first.yaml
    pytest.param("Simpson", 7 / 3, marks=pytest.mark.slow),     # simpson_first.yaml
    ("two 2K-H stages", 100.0),       # models/planetary_2kh_two_stages_100.yaml
    ("K-H-V", -119.0),                # models/cycloid_khv_119.yaml, -z_disc/(z_ring - z_disc)
])
def test_classic_trains_found_at_their_reference_ratios(name, ratio) -> None:
    result = synthesize(ratio, graphs=[CLASSICS[name]], top=3)
    assert result.rows
    for row in result:
        assert abs(row.ratio / ratio - 1) <= 0.005
        check_single_solve(row)
        check_geometry(row, 3)


# --- conditions, one at a time ------------------------------------------------------------
def test_assembly_closed_forms_of_the_textbooks() -> None:
    one = lambda v: np.array([v])  # noqa: E731
    # simple planet: (z_s + z_r)/n whole
    assert assembles([one(12), one(72)], [one(-30), one(30)], 3)[0]
    assert not assembles([one(12), one(73)], [one(-30), one(30)], 3)[0]
    # stepped planet (models/planetary_stepped.yaml): (z_s z_p2 + z_r z_p1)/(n gcd) =
    # (18*18 + 72*36)/(3*18) = 54, whole
    assert assembles([one(18), one(72)], [one(-36), one(18)], 3)[0]
    # Wolfrom (models/wolfrom_3k.yaml): (12 + 72)/3 = 28 and (72*27 - 69*30)/(3*3) = -14
    assert assembles([one(12), one(72), one(69)], [one(-30), one(30), one(27)], 3)[0]
    # sun 13, planet 29/27, rings 71 and 70: (13 + 71)/3 = 28 but (71*27 - 70*29)/3 = -37/3
    assert not assembles([one(13), one(71), one(70)], [one(-29), one(29), one(27)], 3)[0]
    assert assembles([one(13), one(71), one(69)], [one(-29), one(29), one(27)], 3)[0]
    # a crank carrying a disc: every copy identical, so z/n whole (RV-40E: 12 / 2)
    assert assembles([one(12)], [one(-36)], 2, phased=True)[0]
    assert not assembles([one(13)], [one(-36)], 2, phased=True)[0]


def test_assembly_agrees_with_the_brute_force_on_random_stepped_planets() -> None:
    rng = np.random.default_rng(7)
    z = rng.integers(12, 60, size=(200, 5))
    for n in (2, 3, 4, 5):
        got = assembles([z[:, 0], z[:, 1], z[:, 2]], [-z[:, 3], z[:, 3], z[:, 4]], n)
        expected = [fits([(a, p, False), (b, p, True), (c, q, True)], n, False)
                    for a, b, c, p, q in z]
        assert list(got) == expected


def test_neighbour_condition() -> None:
    # sun 12, planet 30: (30 + 2) < (12 + 30) sin(60°) = 36.4 with 3 planets, not with 4
    assert neighbours_clear(np.array(30), np.array(42), 3)
    assert not neighbours_clear(np.array(30), np.array(42), 4)


def test_layouts_of_the_2kh_are_simple_and_stepped() -> None:
    names = [layout.name for layout in layouts(CLASSICS["2K-H"], (12, 40), 3)]
    assert names.count("simple") == 2 and names.count("stepped") == 4


def test_coupling_counts_in_the_mobility() -> None:
    khv = CLASSICS["K-H-V"]
    assert khv.dof == 1
    doc = khv.to_model_dict(frame=0, inputs=(1,), outputs=(3,),
                            teeth={(0, 0): 39, (0, 1): 40}, internal={0: 1})
    assert [link for link in doc["links"] if link["type"] == "coupling"] == [
        {"type": "coupling", "between": ["L2", "L3"]}]
    result = pg.solve(model_from_dict(doc))
    assert_conservation(result)
    assert result.ratio == pytest.approx(-39.0)           # -z_disc/(z_ring - z_disc)


# --- result, errors, parallel -------------------------------------------------------------
def test_result_protocol_and_json() -> None:
    result = synthesize(5, graphs=[CLASSICS["2K-H"]], top=3)
    assert isinstance(result, Result) and len(result) <= 3
    json.dumps(result.to_dict())
    text = result.text_report()
    assert "synthesis for ratio 5 : 1" in text and "eff %" in text
    assert max(len(line) for line in text.splitlines()) <= 100
    assert "sun in, carrier out, ring fixed" in text      # members by role, one set
    ax = result.plot()
    assert [t.get_text() for t in ax.get_xticklabels()] == [r.name for r in result]


@pytest.mark.parametrize("kwargs, message", [
    ({"ratio": 0}, "ratio"), ({"ratio": 5, "tolerance": 0}, "tolerance"),
    ({"ratio": 5, "teeth": (40, 12)}, "teeth"), ({"ratio": 5, "planets": 0}, "planets"),
    ({"ratio": 5, "mesh_efficiency": 1.5}, "mesh efficiency"), ({"ratio": 5, "top": 0}, "top"),
])
def test_bad_arguments_are_usage_errors(kwargs, message) -> None:
    with pytest.raises(UsageError, match=message):
        synthesize(**kwargs)


def test_a_graph_with_two_degrees_of_freedom_is_refused() -> None:
    two = TrainGraph(4, ((0, 1, 0), (0, 3, 0), (3, 2, 1)), ((1, 2, 3),))
    with pytest.raises(UsageError, match="degrees of freedom"):
        synthesize(5, graphs=[two])


def test_map_chunks_in_process_and_addresses() -> None:
    assert map_chunks(abs, [-3, 2, -1]) == [3, 2, 1]
    assert scheduler_address("dask://h:8786") == "tcp://h:8786"
    with pytest.raises(UsageError):
        scheduler_address("h:8786")
    with pytest.raises(UsageError):
        map_chunks(abs, [1], workers=0)


@pytest.mark.slow
def test_dask_local_cluster_matches_the_single_process_run() -> None:
    graphs = [CLASSICS["2K-H"], CLASSICS["RV (2K-H + K-H-V)"]]
    alone = synthesize(121, graphs=graphs, top=None)
    spread = synthesize(121, graphs=graphs, top=None, workers=2)
    assert spread.to_dict() == alone.to_dict()
    assert len(alone) >= 1 and alone.feasible > 1


def test_largest_virtual_power_of_a_set_without_input_power_is_nan() -> None:
    """Mesh losses 2 W and 1 W at η = 0.98 pass 100 W and 50 W of virtual power: over an
    input of 400 W the largest is 0.25. A set taking no input power has no such figure
    (NaN, with no warning: the command line turns warnings into errors)."""
    import types
    import warnings

    from powergraph.analyses.synthesis.rank import _max_virtual_power

    result = types.SimpleNamespace(shape=(2,), input_power=np.array([400.0, 0.0]),
                                   losses={0: np.array([2.0, 0.0]), 1: np.array([1.0, 0.0])})
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ratio = _max_virtual_power(result, 0.98)
    assert ratio[0] == pytest.approx(0.25) and np.isnan(ratio[1])
