"""Every analysis result offers one interface: :class:`powergraph.result.Result`.

``to_dict()`` must be JSON (strict: no NaN), ``text_report()`` a non-empty str, and
``plot(ax=...)`` must draw on the given axes and return it — or, for a result with no
picture, raise :class:`~powergraph.result.NothingToDrawError` (a PowerGraphError).
"""
from __future__ import annotations

import json
from pathlib import Path

import pytest

import powergraph as pg
from powergraph.errors import PowerGraphError
from powergraph.result import NothingToDrawError, Result
from powergraph.testing import assert_conservation

MODELS = Path(__file__).resolve().parents[1] / "models"


def _solved(name: str):
    result = pg.solve(pg.load_model(MODELS / name))
    assert_conservation(result)
    return result


def _power_flow():
    return _solved("rv40e_wang2021.yaml")


def _wang2021():
    from powergraph.methods import solve_wang2021

    result = solve_wang2021(pg.load_model(MODELS / "rv40e_wang2021.yaml"))
    assert_conservation(result.virtual_power_result)
    assert_conservation(result.realisation)
    return result


def _method_comparison():
    from powergraph.methods import compare_methods

    comparison = compare_methods(pg.load_model(MODELS / "rv40e_wang2021.yaml"))
    assert_conservation(comparison.rigorous)
    return comparison


def _figure():
    from powergraph.methods.figures import cycloid_ratio_curves

    return cycloid_ratio_curves(pg.load_model(MODELS / "rv40e_wang2021.yaml"), z5_values=[30, 40])


def _comparison_table():
    from powergraph.analyses.compare import compare_models

    return compare_models([pg.load_model(MODELS / "planetary_2kh_sun_to_carrier.yaml"),
                           pg.load_model(MODELS / "wolfrom_3k.yaml")])


def _backlash():
    from powergraph.analyses.backlash import analyse_backlash

    return analyse_backlash(pg.load_model(MODELS / "backlash_li2012.yaml"))


def _backlash_pair():
    return _backlash().meshes[0].pair


def _centre_distance():
    from powergraph.analyses.backlash import centre_distance_curve

    return centre_distance_curve(2.5, 0.025, 0.018, 45, 40)


def _cycloid_stage():
    from powergraph.analyses.cycloid import cycloid_fluctuation

    return cycloid_fluctuation(module=1, teeth=9, profile_error=0.01)


def _cycloid_study():
    from powergraph.analyses.cycloid import fluctuation_study

    return fluctuation_study(1.0, teeth=(9, 25), grades=(5, 9))   # a small grid


def _cycloid_train():
    from powergraph.analyses.cycloid import train_fluctuation

    return train_fluctuation(pg.load_model(MODELS / "rv40e_profile_error.yaml"))


def _volume():
    from powergraph.analyses.volume import volume

    return volume(pg.load_model(MODELS / "rv40e_wang2021.yaml"))


def _pitch_circle_errors():
    from powergraph.analyses.volume import pitch_circle_errors

    return pitch_circle_errors([17, 30, 60])


def _sweep():
    from powergraph.analyses.sweep import sweep

    return sweep(pg.load_model(MODELS / "rv40e_wang2021.yaml"),
                 {"links.1.efficiency": [0.94, 0.97, 0.998]}, quiet=True)


def _formula():
    from powergraph.analyses.formula import derive_formulas

    return derive_formulas(pg.load_model(MODELS / "planetary_2kh_sun_to_carrier.yaml"))


#: (name, builder, has a picture)
def _tolerance():
    from powergraph.analyses.tolerance import tolerance_analysis

    return tolerance_analysis(pg.load_model(MODELS / "rv40e_tolerances.yaml"), samples=2000,
                              seed=1, specs=["lost_motion<=1arcmin"], sobol_samples=0)


def _efficiency_map():
    from powergraph.analyses.efficiency_map import efficiency_map

    return efficiency_map(pg.load_model(MODELS / "planetary_2kh_sun_to_carrier.yaml"),
                          [10.0, 20.0], [100.0, 200.0], rated_torque=15.0)


def _mesh_loss():
    from powergraph.gears.mesh_loss import MeshGeometry, mesh_loss

    return mesh_loss(MeshGeometry(20, 40), mu=0.05)


def _cycloid_loss():
    from powergraph.gears.cycloid_loss import (CrankBearing, OutputPins, PinContact, PinRing,
                                               cycloid_mesh_loss)

    return cycloid_mesh_loss(PinRing(39, 64.0, 3.0, 1.3), PinContact(0.05),
                             OutputPins(8, 40.0, 0.05), CrankBearing(0.002, 20.0))


def _enumeration():
    from powergraph.analyses.synthesis import enumerate_trains

    return enumerate_trains(4)


def _synthesis():
    from powergraph.analyses.synthesis import synthesize
    from powergraph.analyses.synthesis.synthesize_classics import classic_graphs

    return synthesize(4.0, graphs=classic_graphs(4), top=3)


def _mode_result():
    from powergraph.statics.modes import solve_mode

    result = solve_mode(pg.load_model(MODELS / "simpson_3speed.yaml"), "1")
    assert_conservation(result.result)
    return result


def _gear_table():
    from powergraph.analyses.gear_table import gear_table

    return gear_table(pg.load_model(MODELS / "ravigneaux_4speed.yaml"))


def _lever_diagram():
    from powergraph.analyses.lever import lever_diagram

    result = _solved("simpson_first.yaml")
    return lever_diagram(result.model, result.speeds)


def _cycle():
    import io

    from powergraph.analyses.cycle import cycle
    return cycle(pg.load_model(MODELS / "ths2_power_split.yaml"),
                 io.StringIO("engine.speed [rpm],engine.power [kW],wheels.speed [rpm]\n"
                             "2000,30,400\n1500,15,1400\n"))


RESULTS = [
    ("PowerFlowResult", _power_flow, True),
    ("CycleResult", _cycle, True),
    ("ModeResult", _mode_result, True),
    ("GearTable", _gear_table, True),
    ("LeverDiagram", _lever_diagram, True),
    ("Wang2021Result", _wang2021, True),
    ("MethodComparison", _method_comparison, False),
    ("FigureData", _figure, True),
    ("ComparisonTable", _comparison_table, True),
    ("BacklashReport", _backlash, True),
    ("PairBacklash", _backlash_pair, True),
    ("CentreDistanceCurve", _centre_distance, True),
    ("CycloidFluctuation", _cycloid_stage, True),
    ("FluctuationStudy", _cycloid_study, True),
    ("TrainFluctuation", _cycloid_train, False),
    ("VolumeResult", _volume, False),
    ("ProfileErrorTable", _pitch_circle_errors, True),
    ("SweepResult", _sweep, True),
    ("FormulaResult", _formula, False),
    ("ToleranceResult", _tolerance, True),
    ("EfficiencyMap", _efficiency_map, True),
    ("MeshLoss", _mesh_loss, False),
    ("CycloidLoss", _cycloid_loss, False),
    ("EnumerationResult", _enumeration, True),
    ("SynthesisResult", _synthesis, True),
]


_BUILT: dict = {}


def built(name: str, build):
    """Each result built once for the module (several fixtures use it)."""
    if name not in _BUILT:
        _BUILT[name] = build()
    return _BUILT[name]


#: Results whose building takes a second or so (a Monte Carlo run, a synthesis, a
#: cycloid study, a symbolic derivation): checked by the full suite, not the quick one.
EXPENSIVE = ("ToleranceResult", "SynthesisResult", "FluctuationStudy", "TrainFluctuation",
             "FigureData", "FormulaResult", "CycloidFluctuation")


def _params(results: list) -> list:
    return [pytest.param(r, id=r[0], marks=pytest.mark.slow if r[0] in EXPENSIVE else ())
            for r in results]


@pytest.fixture(scope="module", params=_params(RESULTS))
def case(request):
    name, build, draws = request.param
    return name, built(name, build), draws


def test_is_a_result(case) -> None:
    name, result, _ = case
    assert type(result).__name__ == name
    assert isinstance(result, Result)


def test_to_dict_is_strict_json(case) -> None:
    _, result, _ = case
    data = result.to_dict()
    assert isinstance(data, dict) and data
    text = json.dumps(data, allow_nan=False)
    assert json.loads(text) == json.loads(json.dumps(data))


def test_text_report_is_text(case) -> None:
    _, result, _ = case
    report = result.text_report()
    assert isinstance(report, str) and report.strip()


def test_plot_draws_on_the_given_axes_or_says_why_not(case) -> None:
    from matplotlib.figure import Figure

    _, result, draws = case
    name = type(result).__name__
    projection = "3d" if name == "FluctuationStudy" else None
    ax = Figure().add_subplot(projection=projection)
    if draws:
        assert result.plot(ax=ax) is ax
        assert ax.has_data() or ax.patches or ax.texts
    else:
        with pytest.raises(NothingToDrawError, match="nothing to draw") as info:
            result.plot(ax=ax)
        assert isinstance(info.value, PowerGraphError)


def test_an_object_without_the_methods_is_not_a_result() -> None:
    class Partial:
        def to_dict(self) -> dict:
            return {}

        def text_report(self) -> str:
            return ""

    assert not isinstance(Partial(), Result)


#: Results that show themselves: a one-line repr, an HTML table, a DataFrame.
DISPLAYED = ("ComparisonTable", "BacklashReport", "CycloidFluctuation", "VolumeResult",
             "SweepResult", "ToleranceResult", "EfficiencyMap", "EnumerationResult",
             "SynthesisResult")


@pytest.fixture(scope="module", params=_params([r for r in RESULTS if r[0] in DISPLAYED]))
def shown(request):
    name, build, _ = request.param
    return name, built(name, build)


def test_repr_is_one_short_line(shown) -> None:
    name, result = shown
    text = repr(result)
    assert text.startswith(f"<{name} ") and text.endswith(">")
    assert "\n" not in text and len(text) < 200


def test_repr_html_is_a_small_table(shown) -> None:
    _, result = shown
    page = result._repr_html_()
    assert page.startswith("<table>") and page.endswith("</table>")
    assert page.count("<tr>") <= 1 + 21 + 1          # header, 20 rows, "... more rows"
    assert "<td>" in page and "-0<" not in page


@pytest.mark.slow  # imports pandas
def test_to_dataframe_has_a_row_per_record(shown) -> None:
    pd = pytest.importorskip("pandas")
    _, result = shown
    frame = result.to_dataframe()
    assert isinstance(frame, pd.DataFrame) and len(frame) > 0
    size = getattr(result, "size", None)
    if size is not None:                              # a sweep: one row per variant
        assert len(frame) == size


def test_to_dataframe_without_pandas_says_so(shown, monkeypatch) -> None:
    import sys

    from powergraph.errors import UsageError

    _, result = shown
    monkeypatch.setitem(sys.modules, "pandas", None)    # import pandas -> ImportError
    with pytest.raises(UsageError, match="pip install pandas"):
        result.to_dataframe()
