"""`compare`: rows equal single solves; back-driving and self-locking; table, JSON, chart."""
from __future__ import annotations

import json
from pathlib import Path

import pytest

import powergraph as pg
from powergraph.analyses.compare import compare_models, compare_row
from powergraph.cli.main import main
from powergraph.kinematics import backdriven
from powergraph.model import loads_model
from powergraph.testing import assert_conservation

MODELS = Path(__file__).resolve().parents[2] / "models"
KEYS = {"name", "ratio", "efficiency", "backdrive_efficiency", "backdrive_self_locking",
        "circulating_power", "max_virtual_power_ratio", "meshes"}


def test_rows_match_single_solves_exactly() -> None:
    paths = sorted(MODELS.glob("*.yaml"))
    models = [m for m in map(pg.load_model, paths) if not m.modes]   # modes: below
    for model, row in zip(models, compare_models(models)):
        forward = pg.solve(model)
        assert_conservation(forward)
        assert row.efficiency == forward.efficiency and row.ratio == forward.ratio
        assert row.circulating_power == forward.circulating_power
        assert row.meshes == len(model.meshes)
        assert row.max_virtual_power_ratio == max(
            e.carrier_frame_power for e in forward.meshes) / forward.input_power
        if len(model.inputs) == 1 and len(model.outputs) == 1 and not model.machines:
            back = pg.solve(backdriven(model, forward.input_power))
            assert_conservation(back)
            assert row.backdrive_efficiency == back.efficiency
            assert row.backdrive_self_locking == (back.formal_efficiency <= 0)
            if back.formal_efficiency <= 0:     # every port takes power in
                assert back.efficiency == 0.0
        else:
            assert row.backdrive_efficiency is None and row.backdrive_note


def test_wolfrom_backdriven_at_095_self_locks() -> None:
    row, = compare_models([pg.load_model(MODELS / "wolfrom_3k.yaml")], mesh_efficiency=0.95)
    assert row.backdrive_self_locking is True and row.backdrive_formal_efficiency < 0
    assert row.backdrive_efficiency == 0.0     # from the flows: nothing leaves at a port
    assert row.efficiency > 0 and not row.self_locking


def test_unseen_khv_stage_self_locks_backwards() -> None:
    """Hand derivation. w_p = -w_H/N. Back-driven, the planet feeds T_p (w_p - w_H) =
    T_p w_p (N + 1) > 0 in the eccentric's frame, so the ring receives:
    T_r (-w_H) = -η T_p (w_p - w_H) → T_r = -η T_p (N + 1)/N; T_H = -T_p - T_r;
    η_back = -T_H w_H / (T_p w_p) = (N + 1) η - N, < 0 when η < N/(N + 1)."""
    text = """
name: K-H-V N=49
components: {0: {role: frame}, H: {}, p: {teeth: 49}, r: {teeth: 50, internal: true}, out: {}}
links:
  - {type: mesh, between: [p, r], carrier: H, efficiency: 0.97}
  - {type: fixed, between: [r, 0]}
  - {type: coupling, between: [p, out]}
ports: [{component: H, role: input, speed: 100, power: 10}, {component: out, role: output}]
"""
    row, = compare_models([loads_model(text)])
    n, eta = 49.0, 0.97
    assert row.efficiency == pytest.approx(eta / (n + 1 - n * eta), rel=1e-12)
    assert row.backdrive_formal_efficiency == pytest.approx((n + 1) * eta - n, rel=1e-12)
    assert row.backdrive_efficiency == 0.0 and row.backdrive_self_locking is True


def test_compare_json_has_the_documented_keys(capsys) -> None:
    paths = [str(MODELS / "rv40e_wang2021.yaml"), str(MODELS / "wolfrom_3k.yaml")]
    assert main(["compare", *paths, "--json", "--mesh-efficiency", "0.98"]) == 0
    rows = json.loads(capsys.readouterr().out)
    assert [r["name"] for r in rows] == ["RV-40E (Wang 2021)", "Wolfrom 3K"]
    assert all(KEYS <= set(r) for r in rows)
    single = pg.solve(pg.load_model(paths[0]).with_mesh_efficiency(0.98))
    assert rows[0]["efficiency"] == single.efficiency


def test_compare_table_and_chart(tmp_path, capsys) -> None:
    out = tmp_path / "chart.svg"
    assert main(["compare", str(MODELS / "rv40e_wang2021.yaml"), str(MODELS / "tuplin_256.yaml"),
                 "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "RV-40E" in text and "locks back" in text and out.stat().st_size > 1000
    assert text.splitlines()[-1] == f"wrote {out}"
    assert out.read_text().lstrip().startswith("<?xml")


def test_compare_bad_output_suffix_exits_2(tmp_path) -> None:
    assert main(["compare", str(MODELS / "rv40e_wang2021.yaml"), "-o", str(tmp_path / "x.txt")]) == 2
    assert not (tmp_path / "x.txt").exists()


def test_volume_and_power_density_columns_when_geometry_is_present() -> None:
    from powergraph.analyses.volume import model_volume

    rv = pg.load_model(MODELS / "rv40e_wang2021.yaml")
    row, plain = compare_models([rv, pg.load_model(MODELS / "wolfrom_3k.yaml")])
    total = model_volume(rv).total_mm3
    assert row.volume_mm3 == total
    # power density = output power / volume, in kW/L (1 L = 1e6 mm³)
    assert row.power_density_kw_per_l == pytest.approx(
        pg.solve(rv).output_power / 1000 / (total / 1e6), rel=1e-12)
    assert plain.volume_mm3 is None and plain.power_density_kw_per_l is None


def test_table_shows_locks_for_a_self_locking_back_drive(capsys) -> None:
    """Cycloid K-H-V, N = 119 at η0 = 0.98, back-driven: formal efficiency
    (N + 1) η0 - N = 117.6 - 119 = -1.4 (see test_unseen_khv_stage_self_locks_backwards):
    the table says "locks", the JSON keeps the formal value."""
    path = str(MODELS / "cycloid_khv_119.yaml")
    assert main(["compare", path, "--mesh-efficiency", "0.98"]) == 0
    text = capsys.readouterr().out
    line = next(x for x in text.splitlines() if x.startswith("Cycloid"))
    assert "locks" in line and "-140" not in line
    assert "back %" in text.splitlines()[0]     # the unit in the header, not in the cells
    assert main(["compare", path, "--mesh-efficiency", "0.98", "--json"]) == 0
    row, = json.loads(capsys.readouterr().out)
    assert row["backdrive_formal_efficiency"] == pytest.approx(120 * 0.98 - 119, rel=1e-9)
    assert row["backdrive_efficiency"] == 0.0
    assert row["backdrive_self_locking"] is True


def test_a_locked_back_drive_has_efficiency_0_and_the_reason() -> None:
    """RV-40E with a cycloid-pin mesh at 0.2, back-driven: no consistent direction
    pattern (the brute force of powergraph.testing agrees), so the back-drive locks."""
    from powergraph.testing import consistent_patterns

    rv = pg.load_model(MODELS / "rv40e_wang2021.yaml").with_link(1, efficiency=0.2)
    assert consistent_patterns(backdriven(rv)) == []
    row, = compare_models([rv])
    assert row.backdrive_efficiency == 0.0 and row.backdrive_self_locking is True
    assert row.backdrive_note.startswith("locks: links[")


def test_a_step_up_reads_1_to_n(capsys) -> None:
    """Carrier in, sun out, ring fixed: i = z_s / (z_s + z_r) = 24 / 96 = 1/4, a step-up
    (models/planetary_2kh_carrier_to_sun.yaml): the table says ``1 : 4``, not 0.25."""
    model = pg.load_model(MODELS / "planetary_2kh_carrier_to_sun.yaml")
    assert_conservation(pg.solve(model))
    table = compare_models([model])
    assert table[0].ratio == pytest.approx(0.25)
    row = table.text_report().splitlines()[2]
    assert "1 : 4" in row and "0.25" not in row


def test_a_mode_row_is_its_case_forward_and_coasting() -> None:
    """A row of ``MODEL:MODE`` is the mode's case (``solve --mode``) forward and back-driven
    (``solve --mode --backdrive``); a model with modes needs its mode."""
    from powergraph.errors import UsageError
    from powergraph.statics.case import TrainCase

    model = pg.load_model(MODELS / "simpson_3speed.yaml")
    with pytest.raises(UsageError, match="the model has modes"):
        compare_models([model])
    for mode in model.modes:
        row = compare_row(model, mode)
        forward = TrainCase.of(model, mode).point()
        coast = TrainCase.of(model, mode, backdrive=True).point()
        assert row.efficiency == forward.result.efficiency
        assert row.ratio == forward.result.ratio
        if coast.result is None:          # first gear: F1 overruns when the output drives
            assert row.backdrive_efficiency is None
            assert row.backdrive_note == f"coasting: {coast.verdict}"
        else:
            assert row.backdrive_efficiency == coast.result.efficiency
