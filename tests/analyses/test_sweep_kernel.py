"""The compiled sweep's numba kernels (powergraph.analyses.sweep.kernel) give the numpy
path's answers, variant for variant: statuses, driver codes and passes identical, values
to 1e-12. Expected values: the numpy path (itself checked against the single solve by
tests/test_evaluators_agree.py), the RV's hand-derived closed form (benchmarks/sweep_rv.py)
and the single solve of each variant model where the pattern does not hold.

The kernels run on small arrays here by lowering KERNEL_MIN_VARIANTS; each model compiles
once (module-scoped evaluators), and a kernel already compiled in the process is reused.
"""
from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import powergraph as pg
from powergraph.analyses.sweep import compile as sweep_compile
from powergraph.analyses.sweep import STATUS, compile_sweep
from powergraph.analyses.sweep.backends import applies
from powergraph.errors import PowerGraphError
from powergraph.kinematics import elements_of
from powergraph.model import load_model
from powergraph import testing_trains
from powergraph.statics.friction import loss_block_places

numba = pytest.importorskip("numba")

ROOT = Path(__file__).resolve().parents[2]
MODELS = sorted((ROOT / "models").glob("*.yaml"))
#: Checked without the slow marker: one train of each kind (RV, planetary, two stages).
QUICK = {"rv40e_wang2021.yaml", "planetary_2kh_sun_to_ring.yaml",
         "planetary_2kh_two_stages.yaml"}
REL = 1e-12
FIELDS = ("ratio", "efficiency", "input_power", "output_power", "total_loss")


@pytest.fixture
def kernels_always(monkeypatch):
    """Every run, however small, goes through the kernels."""
    monkeypatch.setattr(sweep_compile, "KERNEL_MIN_VARIANTS", 1)


def assert_same(kernel, numpy_result) -> None:
    """Two sweep results agree variant for variant."""
    for name in ("status", "passes", "self_locking", "converged"):
        assert getattr(kernel, name).tolist() == getattr(numpy_result, name).tolist(), name
    for link in numpy_result.drivers:
        assert kernel.drivers[link].tolist() == numpy_result.drivers[link].tolist()
        np.testing.assert_allclose(kernel.losses[link], numpy_result.losses[link], rtol=REL,
                                   atol=REL * np.nanmax(np.abs(numpy_result.input_power)))
    for name in FIELDS:
        np.testing.assert_allclose(getattr(kernel, name), getattr(numpy_result, name),
                                   rtol=REL, atol=0.0, equal_nan=True, err_msg=name)


def sweep_values(model) -> dict:
    """Every efficiency over a range that reaches back-driving, and a tooth number."""
    values = {"links.*.efficiency": np.array([0.3, 0.6, 0.9, 0.97, 1.0])[:, None]}
    for element in elements_of(model):
        link = model.links[element.link]
        if element.kind == "mesh" and link.ratio is None:
            teeth = model.components[element.a].teeth
            values[f"components.{element.a}.teeth"] = np.array([teeth, teeth + 1, teeth + 3])
            break
    return values


def kernel_applies(model) -> bool:
    if model.buses or loss_block_places(model):
        return False
    try:
        compiled = compile_sweep(model, list(sweep_values(model)), backend="numeric")
    except PowerGraphError:
        return False
    return applies(compiled.layout)


#: Trains the kernels see as one already listed (the same train with other numbers or
#: data: the RV-40E with tolerances or a profile error, the 119-tooth K-H-V, the 100:1 two
#: stages; Ravigneaux gears and 2K-H port choices beyond one of each member as input).
SAME_AS_LISTED = {"rv40e_profile_error.yaml", "rv40e_tolerances.yaml", "cycloid_khv_119.yaml",
                  "planetary_2kh_two_stages_100.yaml", "ravigneaux_second.yaml",
                  "ravigneaux_reverse.yaml", "planetary_2kh_carrier_to_ring.yaml",
                  "planetary_2kh_ring_to_sun.yaml", "planetary_2kh_sun_to_carrier.yaml"}
#: Models whose kernel is another model's but for its numbers: the generated source is the
#: same up to its float literals (the same closed form, checks, driver codes and writes),
#: so the kernel test runs its partner's only; test_kernel_twins_differ_only_in_numbers
#: keeps this table true (a twin that changes structure fails there).
KERNEL_TWINS = {
    "cycloid_khv_119.yaml": "cycloid_khv.yaml",             # other teeth
    "khv_involute.yaml": "cycloid_khv.yaml",                # an involute K-H-V stage
    "planetary_stepped.yaml": "planetary_2kh_sun_to_carrier.yaml",
    "planetary_2kh_two_stages_100.yaml": "planetary_2kh_two_stages.yaml",
    "rv40e_profile_error.yaml": "rv40e_wang2021.yaml",      # the same source, byte for byte:
    "rv40e_tolerances.yaml": "rv40e_wang2021.yaml",         # blocks the sweep does not read
}
MARKED = [pytest.param(p, marks=() if p.name in QUICK else pytest.mark.slow, id=p.name)
          for p in MODELS if p.name not in SAME_AS_LISTED | KERNEL_TWINS.keys()]


@pytest.mark.parametrize("path", MARKED)
def test_every_model_through_the_kernels(path: Path, kernels_always) -> None:
    model = load_model(path)
    if not kernel_applies(model):
        pytest.skip("the symbolic backend (hence the kernels) does not apply")
    values = sweep_values(model)
    fast = compile_sweep(model, list(values))
    if not fast.patterns:
        pytest.skip("the model settles on no closed form")
    kernel = fast(values, quiet=True)
    assert fast.kernel_compile_s > 0          # a kernel ran
    sweep_compile.KERNEL_MIN_VARIANTS = 10**18
    assert_same(kernel, compile_sweep(model, list(values))(values, quiet=True))


def kernel_sources(path: Path) -> list[str]:
    """The sources of the kernels test_every_model_through_the_kernels compiles for the
    model (one per closed form it settles on), float literals replaced by ``#``; nothing
    is compiled."""
    model = load_model(path)
    values = sweep_values(model)
    compiled = compile_sweep(model, list(values))
    kernels = sweep_compile.kernel_module()
    lines = compiled._input_lines(kernels, (False,) * len(values))
    return sorted(re.sub(r"\d+\.\d+(e[-+]?\d+)?", "#",
                         kernels.kernel_source(form, len(values), *lines, cache=False))
                  for form in compiled._closed_forms)


@pytest.mark.slow  # two symbolic compiles
@pytest.mark.parametrize("twin", sorted(KERNEL_TWINS))
def test_kernel_twins_differ_only_in_numbers(twin: str) -> None:
    twin_sources = kernel_sources(ROOT / "models" / twin)
    assert twin_sources
    assert twin_sources == kernel_sources(ROOT / "models" / KERNEL_TWINS[twin])


# --- the RV: its hand-derived closed form, its back-driven variants -----------------------

RV = ROOT / "models" / "rv40e_wang2021.yaml"
PATHS = testing_trains.RV_PATHS
POWER = 2270.0


@pytest.fixture(scope="module")
def rv_sweep():
    return compile_sweep(load_model(RV), list(PATHS))


def rv_variants(n: int, seed: int = 1) -> dict:
    return testing_trains.rv_variants(n, seed)


def test_rv_variants_equal_the_hand_derivation(rv_sweep, kernels_always) -> None:
    """ratio = 1 + z2 z5/(z1 (z5 - z4)), η = [1 + (z2/z1) η1 z5/(z5 - z4 η2)]/ratio,
    L_12 = P (1 - 1/i)(1 - η1), total loss P (1 - η) (benchmarks/sweep_rv.py)."""
    values = rv_variants(3000)
    z1, z2, z4, z5, eta1, eta2 = (values[p] for p in PATHS)
    result = rv_sweep(values, quiet=True)
    assert rv_sweep.kernel_compile_s > 0
    ratio = 1.0 + z2 * z5 / (z1 * (z5 - z4))
    efficiency = (1.0 + (z2 / z1) * eta1 * z5 / (z5 - z4 * eta2)) / ratio
    assert np.all(result.status == 0)
    np.testing.assert_allclose(result.ratio, ratio, rtol=1e-12)
    np.testing.assert_allclose(result.efficiency, efficiency, rtol=1e-12)
    np.testing.assert_allclose(result.total_loss, POWER * (1.0 - efficiency), rtol=1e-9)
    np.testing.assert_allclose(result.losses[0], POWER * (1.0 - 1.0 / ratio) * (1.0 - eta1),
                               rtol=1e-9)
    assert result.drivers[0].tolist() == [1] * 3000       # the input pinion drives
    assert result.drivers[1].tolist() == [-1] * 3000      # the needle gear drives


def test_one_value_for_every_variant(rv_sweep, kernels_always) -> None:
    """A scalar among the arrays (its own kernel: read at index 0)."""
    values = rv_variants(500)
    values["components.1.teeth"] = 12
    kernel = rv_sweep(values, quiet=True)
    sweep_compile.KERNEL_MIN_VARIANTS = 10**18
    assert_same(kernel, compile_sweep(load_model(RV), list(PATHS))(values, quiet=True))


def test_back_driven_variants_are_the_single_solve(kernels_always) -> None:
    """Power fed in at the output (a negative input power) back-drives the RV: the
    model's pattern fails there, and those variants get the single solve's answer."""
    model = load_model(RV)
    values = {"ports.0.power": np.array([2270.0, -2270.0, 50.0, -1.0]),
              "links.1.efficiency": np.array([0.94, 0.99, 0.97, 0.999])}
    compiled = compile_sweep(model, list(values))
    result = compiled(values, quiet=True)
    assert compiled.kernel_compile_s > 0
    assert result.drivers[1].tolist()[:1] == [-1] and -1 in result.drivers[0].tolist()
    for j in range(4):
        single = pg.solve(compiled.variant(values, j))
        assert STATUS[result.status[j]] == ("locked" if single.lock else "ok")
        assert result.efficiency[j] == pytest.approx(single.efficiency, rel=1e-11)
        assert result.input_power[j] == pytest.approx(single.input_power, rel=1e-11)
        assert [int(result.drivers[e.link][j]) for e in single.elements] == [
            0 if e.driver is None else (1 if e.driver == e.a else -1) for e in single.elements]


# --- when the kernels are used ------------------------------------------------------------

def test_without_numba_the_sweep_uses_numpy(rv_sweep, kernels_always, monkeypatch) -> None:
    values = rv_variants(200, seed=3)
    monkeypatch.setitem(sys.modules, "numba", None)        # `import numba` fails
    fresh = compile_sweep(load_model(RV), list(PATHS))
    assert sweep_compile.kernel_module() is None
    without = fresh(values, quiet=True)
    assert fresh.kernel_compile_s == 0
    monkeypatch.delitem(sys.modules, "numba")
    assert_same(rv_sweep(values, quiet=True), without)


def test_a_kernel_that_fails_warns_and_leaves_the_answer_to_numpy(rv_sweep, kernels_always,
                                                                  monkeypatch) -> None:
    """A kernel that cannot compile (numba's typing error, say) changes no number."""
    values = rv_variants(200, seed=4)
    expected = rv_sweep(values, quiet=True)
    fresh = compile_sweep(load_model(RV), list(PATHS))

    class Broken:
        def __init__(self, *args, **kwargs) -> None:
            raise TypeError("no typing for this")

    monkeypatch.setattr(sweep_compile.kernel_module(), "Kernel", Broken)
    with pytest.warns(sweep_compile.KernelFallbackWarning, match="TypeError"):
        got = fresh(values, quiet=True)
    assert_same(expected, got)


def test_small_runs_and_solve_import_no_numba() -> None:
    code = ("import sys, numpy as np\nimport powergraph as pg\n"
            "from powergraph.model import load_model\n"
            "from powergraph.analyses.sweep import sweep\n"
            f"m = load_model({str(RV)!r})\npg.solve(m)\nassert 'numba' not in sys.modules\n"
            "sweep(m, {'links.1.efficiency': np.linspace(0.9, 1.0, 1000)}, quiet=True)\n"
            "print('numba' in sys.modules)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, cwd=ROOT)
    assert out.stdout.strip() == "False"


def test_kernels_are_kept_in_the_cache_directory(rv_sweep, kernels_always, tmp_path,
                                                 monkeypatch) -> None:
    """The generated source goes to $POWERGRAPH_CACHE_DIR; "" keeps it in memory; a
    directory that cannot be made is left silently for memory (where the kernel already
    compiled in memory is reused)."""
    from powergraph.analyses.sweep import kernel

    values = rv_variants(100, seed=4)
    expected = rv_sweep(values, quiet=True)
    functions = []
    for setting, files in ((str(tmp_path / "k"), 1), ("", 0), ("/proc/no/such/dir", 0)):
        monkeypatch.setenv(kernel.CACHE_ENV, setting)
        fresh = compile_sweep(load_model(RV), list(PATHS))
        assert_same(fresh(values, quiet=True), expected)
        assert fresh.kernel_compile_s > 0
        written = list((tmp_path / "k").glob("powergraph_kernel_*.py"))
        assert len(written) == 1 if files else True
        functions.append({f for k in fresh._kernels.values() for f in k._functions.values()})
    assert kernel.cache_directory() is None
    assert functions[1] == functions[2] and functions[0].isdisjoint(functions[1])


def test_a_learned_pattern_gets_its_own_kernel(kernels_always) -> None:
    """Half the variants back-driven: the first run learns their pattern through numpy,
    the second runs both kernels (the second on the variants the first left)."""
    model = load_model(RV)
    rng = np.random.default_rng(5)
    values = {"ports.0.power": np.where(np.arange(4096) % 2 == 0, 2270.0, -2270.0),
              "links.*.efficiency": rng.uniform(0.995, 1.0, 4096)}
    compiled = compile_sweep(model, list(values))
    first = compiled(values, quiet=True)
    assert len(compiled.patterns) == 2
    second = compiled(values, quiet=True)
    assert sum(k is not None for k in compiled._kernels.values()) == 2
    sweep_compile.KERNEL_MIN_VARIANTS = 10**18
    expected = compile_sweep(model, list(values))(values, quiet=True)
    assert_same(first, expected)
    assert_same(second, expected)


# --- what the kernels leave to numpy ----------------------------------------------------

def chain(n: int, eta: float):
    """``n`` gears on fixed axes in a row, input power 100 W at gear 1, each mesh of
    efficiency ``eta``."""
    from powergraph.model import loads_model
    from powergraph.testing_trains import gear_chain_text

    return loads_model(gear_chain_text(n)).with_mesh_efficiency(eta)


def test_codes_the_bound_cannot_decide_are_left_to_numpy(kernels_always) -> None:
    """At η = 1e-6 per mesh the last mesh's force is 1e-12 of the first's: far above
    round-off on its own bodies (it passes power, η^3 arrives), below 1e-10 of the whole
    train's torques. The kernel reads its code on that bound, cannot decide it, and
    takes no variant: numpy gives every one the single solve's answer."""
    model = chain(4, 1e-6)
    values = {"links.*.efficiency": np.full(300, 1e-6)}
    compiled = compile_sweep(model, list(values))
    result = compiled(values, quiet=True)
    (kernel,) = [k for k in compiled._kernels.values() if k is not None]
    out = sweep_compile.Outputs.empty(300, 3)
    valid, rejected = kernel([values["links.*.efficiency"]], out)
    assert rejected == 300 and not valid.any()
    single = pg.solve(model)
    assert single.efficiency == pytest.approx(1e-18, rel=1e-12)
    np.testing.assert_allclose(result.efficiency, single.efficiency, rtol=1e-12)
    assert np.all(result.status == 0)


@pytest.mark.parametrize("bad, words", [
    (("links.1.efficiency", 37, 1.5), "efficiency must be in (0, 1]; got 1.5"),
    (("components.4.teeth", 5, 0), "teeth must be whole numbers >= 1"),
    (("components.1.teeth", 9, 12.5), "teeth must be whole numbers >= 1"),
    (("links.0.efficiency", 0, np.nan), "efficiency must be in (0, 1]; got nan")])
def test_values_out_of_range_are_refused_as_without_kernels(bad, words,
                                                             kernels_always) -> None:
    """The kernels check the swept arrays' values themselves (no numpy pass before them):
    a value out of range still raises, with the PATH and the message of the numpy path."""
    path, index, value = bad
    values = rv_variants(400)
    if not float(value).is_integer():       # a whole number stays in its integer array
        values[path] = values[path].astype(float)
    values[path][index] = value
    messages = []
    for least in (1, 10**18):
        sweep_compile.KERNEL_MIN_VARIANTS = least
        with pytest.raises(PowerGraphError, match=path.replace(".", r"\.")) as caught:
            compile_sweep(load_model(RV), list(PATHS))(values, quiet=True)
        messages.append(str(caught.value))
    assert words in messages[0]
    assert messages[0] == messages[1]


def test_a_scalar_out_of_range_is_refused(rv_sweep, kernels_always) -> None:
    values = rv_variants(300)
    values["links.0.efficiency"] = 1.2
    with pytest.raises(PowerGraphError, match=r"links\.0\.efficiency"):
        rv_sweep(values, quiet=True)


def test_a_forked_process_runs_kernels_after_its_parent() -> None:
    """The kernels' thread pool survives fork (GNU OpenMP, numba's default without TBB,
    aborts such a child): a sweep, then two forked workers sweeping. (The RV variants of
    rv_sweep: the kernel the session compiled for them, if it did, is loaded from the
    cache directory instead of compiled again.)"""
    code = ("import multiprocessing\n"
            "from powergraph.analyses.sweep import compile as c, compile_sweep\n"
            "from powergraph.model import load_model\n"
            "from powergraph.testing_trains import rv_variants\n"
            "c.KERNEL_MIN_VARIANTS = 1\n"
            f"m = load_model({str(RV)!r})\n"
            "values = rv_variants(500)\n"
            "def run(_):\n"
            "    s = compile_sweep(m, list(values))\n"
            "    r = s(values, quiet=True)\n"
            "    assert s.kernel_compile_s > 0\n"
            "    return float(r.efficiency[0])\n"
            "first = run(0)\n"
            "with multiprocessing.get_context('fork').Pool(2) as pool:\n"
            "    print(pool.map(run, [1, 2]) == [first, first])\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         cwd=ROOT, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "True"
