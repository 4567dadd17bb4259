"""The library never chooses a matplotlib backend: the user's choice holds.

Run in fresh processes, since the test session itself runs with MPLBACKEND=Agg.
"""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def run_python(code: str, backend: str | None) -> str:
    env = {k: v for k, v in os.environ.items() if k != "MPLBACKEND"}
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT), env.get("PYTHONPATH")]))
    if backend is not None:
        env["MPLBACKEND"] = backend
    return subprocess.run([sys.executable, "-c", code], env=env, cwd=ROOT, check=True,
                          capture_output=True, text=True).stdout.strip()


def test_importing_the_plot_package_keeps_mplbackend() -> None:
    """The acceptance check, as a user would type it."""
    out = run_python("import powergraph.plot, matplotlib; print(matplotlib.get_backend())",
                     "svg")
    assert out == "svg"


@pytest.mark.parametrize("backend", ["svg", "pdf"])
def test_drawing_keeps_mplbackend(backend: str) -> None:
    """Import every plot module and draw a diagram through pyplot: still the user's."""
    code = ("import matplotlib, powergraph as pg\n"
            "import powergraph.plot.power_flow, powergraph.plot.wang2021, "
            "powergraph.plot.cycloid, powergraph.plot.backlash, powergraph.plot.volume, "
            "powergraph.plot.sweep, powergraph.plot.compare\n"
            "ax = pg.solve(pg.load_model('models/rv40e_wang2021.yaml')).plot(frame='3')\n"
            "print(matplotlib.get_backend(), type(ax.figure.canvas).__module__)\n")
    name, canvas = run_python(code, backend).split()
    assert name == backend
    assert canvas == f"matplotlib.backends.backend_{backend}"


def test_importing_the_plot_package_imports_no_matplotlib() -> None:
    out = run_python("import sys, powergraph.plot, powergraph.plot.layout.layout, "
                     "powergraph.plot.layout.fold, powergraph.plot.lever_layout\n"
                     "print(sorted(m for m in sys.modules if m.split('.')[0] == 'matplotlib'))",
                     None)
    assert out == "[]"


@pytest.mark.slow
def test_solve_and_the_layouts_import_no_matplotlib() -> None:
    """``powergraph solve`` never loads matplotlib, nor do the figures' layouts (the
    folded flow diagram, the levers): the numbers never depend on a drawing."""
    code = ("import io, sys, contextlib\n"
            "from powergraph.cli.main import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n"
            "    main(['solve', 'models/ths2_power_split.yaml'])\n"
            "import powergraph as pg\n"
            "from powergraph.analyses.lever import lever_diagram\n"
            "from powergraph.plot.layout.layout import layout_flow\n"
            "from powergraph.plot.layout.view import flow_view\n"
            "from powergraph.plot.lever_layout import layout_levers\n"
            "result = pg.solve(pg.load_model('models/ths2_power_split.yaml'))\n"
            "layout_flow(flow_view(result)), layout_levers(lever_diagram(result.model, "
            "result.speeds))\n"
            "print(sorted(m for m in sys.modules if m.split('.')[0] == 'matplotlib'))")
    assert run_python(code, None) == "[]"
