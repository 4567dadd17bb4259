"""Every notebook in notebooks/ runs top to bottom without error (so none can rot).

Each is executed from its own folder, as ``jupyter nbconvert --execute`` or a Jupyter
server started in ``notebooks/`` runs it: the notebooks reach the models as
``../models/...``. Only nbclient and nbformat are needed (not nbconvert).
"""
from __future__ import annotations

import json
from pathlib import Path

import pytest

NOTEBOOK_DIR = Path(__file__).resolve().parents[1] / "notebooks"
NOTEBOOKS = sorted(NOTEBOOK_DIR.glob("*.ipynb"))


@pytest.mark.slow  # a kernel each, several seconds
@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_runs_from_its_own_folder(path: Path) -> None:
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    notebook = nbformat.read(path, as_version=4)
    client = nbclient.NotebookClient(notebook, timeout=600, kernel_name="python3",
                                     resources={"metadata": {"path": str(path.parent)}})
    client.execute()


@pytest.mark.parametrize("path", NOTEBOOKS, ids=[p.stem for p in NOTEBOOKS])
def test_notebook_paths_are_relative_to_the_notebook(path: Path) -> None:
    """A quick check of the same rule: every ``models/...`` file named in a code cell
    exists relative to notebooks/ (a path from the repository root fails there)."""
    import re

    cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
    code = "".join("".join(c["source"]) for c in cells if c["cell_type"] == "code")
    for name in re.findall(r'["\']([^"\'{}]*models/[^"\'{}]+\.yaml)["\']', code):
        assert (NOTEBOOK_DIR / name).resolve().is_file(), f"{path.name}: {name}"
