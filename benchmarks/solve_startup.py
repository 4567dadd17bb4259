"""How fast one solve is: in-process solves against a reference commit, and the start-up
of `powergraph solve --json` against `python -c "import numpy, yaml"`.

In-process: the constant-efficiency RV-40E, the Wolfrom drive and the friction RV-40E,
each solved repeatedly in a fresh process of this tree and of the reference commit
(``--reference``, default a05e997, extracted with ``git archive`` into a temporary
directory), the two alternating so that a busy machine slows both alike. Each tree's own
model files are used; the files are named explicitly (the constant-efficiency RV-40E is
``models/rv40e_wang2021.yaml`` where it exists, else ``models/rv40e.yaml`` when that file
has no friction law; the friction RV is ``models/rv40e_friction.yaml``, else
``models/rv40e.yaml`` when that one has). A model with a heat balance (``thermal:``) is
solved at its lubricant's own temperature, the work the reference commit does; the same
solve with its heat balance (a whole solve per step of the balance) is reported on its own
line, ``heat_balance``, against the fixed-temperature solve of this tree.

Start-up: whole-process time of `powergraph solve MODEL --json` against the time of
`python -c "import numpy, yaml"` (what any run needs anyway), alternating too.

Both trees are byte-compiled first (``compileall``), as an installed package is, and as
numpy and yaml in site-packages are: a shell with ``PYTHONDONTWRITEBYTECODE`` set never
writes the ``.pyc`` files of an editable install, and would time the compiler instead.

Usage: python benchmarks/solve_startup.py [--rounds N] [--reference COMMIT] [--json]
"""
from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tarfile
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: (label, candidate model files in order, whether the file must carry a friction law)
MODELS = (("RV-40E, constant efficiencies", ("models/rv40e_wang2021.yaml", "models/rv40e.yaml"),
           False),
          ("Wolfrom 3K", ("models/wolfrom_3k.yaml",), False),
          ("RV-40E, friction", ("models/rv40e_friction.yaml", "models/rv40e.yaml"), True))

#: Run in a fresh process with PYTHONPATH set to a tree: ms per solve (best of 5 batches).
CHILD = """
import dataclasses, sys, timeit
import powergraph as pg
model = pg.load_model(sys.argv[1])
if sys.argv[3] == "fixed" and getattr(model, "thermal", None) is not None:
    model = dataclasses.replace(model, thermal=None)   # at the lubricant's own temperature
pg.solve(model)
n = int(sys.argv[2])
print(min(timeit.repeat(lambda: pg.solve(model), number=n, repeat=5)) / n * 1e3)
"""


def model_file(tree: Path, candidates: tuple[str, ...], friction: bool) -> str:
    """The first candidate in ``tree`` with (or without) a friction law."""
    for name in candidates:
        path = tree / name
        if path.exists() and (("friction:" in path.read_text() or "pins:" in path.read_text())
                              == friction):
            return name
    raise FileNotFoundError(f"{tree}: none of {candidates} (friction={friction})")


def in_process_ms(tree: Path, name: str, number: int, how: str = "fixed") -> float:
    env = {**os.environ, "PYTHONPATH": str(tree)}
    out = subprocess.run([sys.executable, "-c", CHILD, name, str(number), how], cwd=tree,
                         env=env,
                         check=True, capture_output=True, text=True)
    return float(out.stdout.strip())


def wall_s(command: list[str], tree: Path) -> float:
    env = {**os.environ, "PYTHONPATH": str(tree)}
    start = time.perf_counter()
    subprocess.run(command, cwd=tree, env=env, check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - start


def extract(commit: str, into: Path) -> Path:
    """``git archive COMMIT`` of this repository, unpacked into ``into``."""
    archive = into / "tree.tar"
    with open(archive, "wb") as handle:
        subprocess.run(["git", "archive", commit], cwd=ROOT, check=True, stdout=handle)
    with tarfile.open(archive) as tar:
        tar.extractall(into / "tree", filter="data")
    return into / "tree"


def byte_compile(tree: Path) -> None:
    """Write the ``.pyc`` files of ``tree``'s package (as ``pip install`` does)."""
    subprocess.run([sys.executable, "-m", "compileall", "-q", str(tree / "powergraph")],
                   check=True, stdout=subprocess.DEVNULL)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--reference", default="a05e997")
    parser.add_argument("--number", type=int, default=200, help="solves per batch")
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        reference = extract(args.reference, Path(tmp))
        byte_compile(ROOT)
        byte_compile(reference)
        for label, candidates, friction in MODELS:
            number = max(1, args.number // (10 if friction else 1))
            ours, theirs = [], []
            name_ours = model_file(ROOT, candidates, friction)
            name_theirs = model_file(reference, candidates, friction)
            for _ in range(args.rounds):
                ours.append(in_process_ms(ROOT, name_ours, number))
                theirs.append(in_process_ms(reference, name_theirs, number))
            rows.append({"solve": label, "file": name_ours, "ms": statistics.median(ours),
                         f"ms_at_{args.reference}": statistics.median(theirs),
                         "ratio": statistics.median(ours) / statistics.median(theirs)})
        name_ours = model_file(ROOT, MODELS[-1][1], True)
        if "thermal:" in (ROOT / name_ours).read_text():
            fixed, balanced = [], []
            for _ in range(args.rounds):
                fixed.append(in_process_ms(ROOT, name_ours, number, "fixed"))
                balanced.append(in_process_ms(ROOT, name_ours, number, "balance"))
            rows.append({"solve": "RV-40E, friction, heat balance", "file": name_ours,
                         "ms": statistics.median(balanced),
                         "ms_at_fixed_temperature": statistics.median(fixed),
                         "heat_balance": statistics.median(balanced)
                         / statistics.median(fixed)})
    name = model_file(ROOT, MODELS[0][1], False)
    solve = [sys.executable, "-m", "powergraph.cli.main", "solve", name, "--json"]
    imports = [sys.executable, "-c", "import numpy, yaml"]
    wall_s(solve, ROOT)                                   # warm the file cache
    solve_times, import_times = [], []
    for _ in range(args.rounds):
        solve_times.append(wall_s(solve, ROOT))
        import_times.append(wall_s(imports, ROOT))
    startup = {"command": f"powergraph solve {name} --json",
               "s": statistics.median(solve_times),
               "import_numpy_yaml_s": statistics.median(import_times),
               "ratio": statistics.median(solve_times) / statistics.median(import_times)}
    if args.json:
        print(json.dumps({"in_process": rows, "startup": startup}))
        return
    for row in rows:
        if "heat_balance" in row:
            print(f"{row['solve']:<32}{row['ms']:8.3f} ms  at a fixed temperature: "
                  f"{row['ms_at_fixed_temperature']:8.3f} ms  ratio {row['heat_balance']:.2f}")
            continue
        print(f"{row['solve']:<32}{row['ms']:8.3f} ms  at {args.reference}: "
              f"{row[f'ms_at_{args.reference}']:8.3f} ms  ratio {row['ratio']:.2f}")
    print(f"{startup['command']:<32}{startup['s']:8.3f} s   import numpy, yaml: "
          f"{startup['import_numpy_yaml_s']:.3f} s  ratio {startup['ratio']:.2f}")


if __name__ == "__main__":
    main()
