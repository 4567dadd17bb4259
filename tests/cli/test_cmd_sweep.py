"""``powergraph sweep MODEL --set PATH=START:STOP:N ... [-o FILE.csv] [--plot FILE]``.

Expected values: single solves of the modified model (``powergraph.solve``) and the RV's
ratio 1 + z2·z5/(z1·(z5 − z4)) (Willis' relation, derived in benchmarks/sweep_rv.py).
"""
from __future__ import annotations

import csv
import io
from pathlib import Path

import pytest

import powergraph as pg
from powergraph.cli.main import main
from powergraph.model import load_model

ROOT = Path(__file__).resolve().parents[2]
RV40E = str(ROOT / "models" / "rv40e_wang2021.yaml")


def run(capsys, *argv: str) -> tuple[int, str, str]:
    status = main(["sweep", *argv])
    out, err = capsys.readouterr()
    return status, out, err


def rows(text: str) -> list[dict]:
    """The CSV's rows by column name, the unit (``[W]``) taken off each header."""
    return [{key.split(" [")[0]: value for key, value in row.items()}
            for row in csv.DictReader(io.StringIO(text))]


def test_grid_to_stdout_matches_single_solves(capsys) -> None:
    status, out, err = run(capsys, RV40E, "--set", "links.1.efficiency=0.9:1:3",
                           "--set", "components.1.teeth=10:14:3", "--quiet")
    assert status == 0, err
    table = rows(out)
    assert list(table[0]) == ["links.1.efficiency", "components.1.teeth", "ratio",
                              "efficiency"]
    assert [(r["links.1.efficiency"], r["components.1.teeth"]) for r in table] == [
        (e, z) for e in ("0.9", "0.95", "1.0") for z in ("10", "12", "14")]
    rv = load_model(RV40E)
    for row in table:
        z1 = int(row["components.1.teeth"])
        assert float(row["ratio"]) == pytest.approx(1 + 36 * 40 / z1, rel=1e-12)
        if z1 == 12:
            single = pg.solve(rv.with_link(1, efficiency=float(row["links.1.efficiency"])))
            assert float(row["efficiency"]) == pytest.approx(single.efficiency, rel=1e-12)
    assert "9 variants, 0 self-locking" in err


def test_output_file_and_all_columns(capsys, tmp_path) -> None:
    target = tmp_path / "sweep.csv"
    status, out, err = run(capsys, RV40E, "--set", "links.*.efficiency=0.94,0.99",
                           "-o", str(target), "--all-columns")
    assert status == 0, err
    assert f"wrote {target}" in out
    header = target.read_text().splitlines()[0].split(",")
    assert header[:3] == ["links.*.efficiency [-]", "ratio [-]", "efficiency [-]"]
    assert {"input_power [W]", "total_loss [W]", "loss_link_1 [W]", "status"} <= set(header)
    table = rows(target.read_text())
    assert len(table) == 2
    assert {"input_power", "output_power", "total_loss", "self_locking", "converged",
            "status", "loss_link_0", "loss_link_1"} <= set(table[0])
    single = pg.solve(load_model(RV40E).with_mesh_efficiency(0.94))
    assert float(table[0]["efficiency"]) == pytest.approx(0.287376, abs=5e-7)
    assert float(table[0]["total_loss"]) == pytest.approx(single.total_loss, rel=1e-12)
    assert table[0]["status"] == "ok" and table[0]["self_locking"] == "false"
    assert not list(tmp_path.glob(".sweep.*"))         # no temporary file left


def test_plot_writes_a_png(capsys, tmp_path) -> None:
    target = tmp_path / "sweep.png"
    status, _, err = run(capsys, RV40E, "--set", "links.1.efficiency=0.9:1:11",
                         "--set", "links.0.efficiency=0.9,0.98", "--plot", str(target))
    assert status == 0, err
    assert target.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_backdriven_self_locking_and_locking_are_reported(capsys, tmp_path) -> None:
    # a back-driven RV (output 6 drives): self-locking below η2 = 39/40; for very lossy
    # meshes the directions cycle and the single solver's search locks the train, at rest
    # (see tests/analyses/test_sweep.py)
    text = Path(RV40E).read_text()
    text = text.replace("- {component: 1, role: input, speed: 1500 rpm, power: 2.27 kW}",
                        "- {component: 1, role: output}")
    text = text.replace("- {component: 6, role: output}",
                        "- {component: 6, role: input, speed: 1.2981767 rad/s, "
                        "power: 2.27 kW}")
    model = tmp_path / "rv_back.yaml"
    model.write_text(text)
    status, out, err = run(capsys, str(model), "--set", "links.1.efficiency=0.1,0.97,0.99",
                           "--all-columns")
    assert status == 0, err
    table = rows(out)
    assert [r["status"] for r in table] == ["locked", "ok", "ok"]
    assert float(table[0]["efficiency"]) == 0.0 and table[0]["converged"] == "true"
    assert [r["self_locking"] for r in table] == ["true", "true", "false"]
    assert "2 self-locking (1 locked at rest)" in err and "not solved" not in err


@pytest.mark.parametrize("argv, words", [
    (["--set", "links.1.efficiency"], "expected PATH=START:STOP:N"),
    (["--set", "links.1.efficiency=0.9:1"], "START:STOP:N"),
    (["--set", "links.1.efficiency=0.9:1:many"], "N must be a whole number"),
    (["--set", "links.1.efficiency=0.9:1.2:3"], "links.1.efficiency: efficiency must be"),
    (["--set", "components.1.teeth=10:13:3"], "components.1.teeth: teeth must be whole"),
    (["--set", "components.9.teeth=10:12:3"], "unknown component '9'"),
    # these three once ended in "numerical problem" (exit 1) or a numpy traceback
    (["--set", "components.1.teeth=1e308"], "components.1.teeth: teeth must be whole"),
    (["--set", "links.1.efficiency=0.9:1:999999999999"], "N must be at most"),
    (["--set", "links.1.efficiency=-inf:1:3"], "not a finite number"),
    (["--set", "links.1.efficiency=0.9", "-o", "missing/x.csv"], "-o: folder 'missing'"),
    (["--set", "links.2.efficiency=0.9:1:2"], "fixed link"),
    (["--set", "bogus=1"], "must start with"),
    (["--set", "links.1.efficiency=0.9", "--set", "links.1.efficiency=1"], "given twice"),
    (["--set", "links.1.efficiency=0.9", "--plot", "out.txt"], "suffix"),
])
def test_bad_arguments_exit_2(capsys, argv, words) -> None:
    status, out, err = run(capsys, RV40E, *argv)
    assert status == 2
    assert words in err
    assert "Traceback" not in err and out == ""


def test_set_is_required(capsys) -> None:
    with pytest.raises(SystemExit) as info:
        main(["sweep", RV40E])
    assert info.value.code == 2


def test_invalid_model_exits_2(capsys, tmp_path) -> None:
    bad = tmp_path / "bad.yaml"
    bad.write_text("name: x\ncomponents: {0: {role: frame}}\nlinks: []\nports: []\n")
    status, _, err = run(capsys, str(bad), "--set", "links.0.efficiency=0.9")
    assert status == 2 and "powergraph: error" in err


@pytest.mark.parametrize("argv, words", [
    (("--workers", "0"), "--workers 0"), (("--workers", "two"), "--workers two"),
    (("--scheduler", "localhost:8786"), "dask://")])
def test_bad_cluster_options_exit_2(capsys, argv, words) -> None:
    status, out, err = run(capsys, RV40E, "--set", "links.1.efficiency=0.9:1:3", *argv)
    assert status == 2 and out == "" and words in err and err.count("\n") == 1


@pytest.mark.slow  # starts a local cluster of two worker processes
def test_two_workers_print_the_same_table(capsys) -> None:
    argv = (RV40E, "--set", "links.1.efficiency=0.9:1:5", "--set",
            "components.1.teeth=10:14:3", "--quiet")
    status, alone, _ = run(capsys, *argv)
    status_2, on_cluster, err = run(capsys, *argv, "--workers", "2")
    assert status == status_2 == 0, err
    assert on_cluster == alone


def test_port_columns_carry_si_units(capsys) -> None:
    """A speed given in rpm is written in rad/s, and its header says so (1500 rpm =
    1500·2π/60 = 157.0796 rad/s)."""
    status, out, err = run(capsys, RV40E, "--set", "ports.0.speed=1500rpm", "--quiet")
    assert status == 0, err
    header, row = out.splitlines()[:2]
    assert header.split(",")[0] == "ports.0.speed [rad/s]"
    assert float(row.split(",")[0]) == pytest.approx(1500 * 2 * 3.141592653589793 / 60)
