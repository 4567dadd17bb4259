"""A train as an FMI 2.0 co-simulation FMU, built with pythonfmu (the optional extra
``pip install -e ".[fmu]"``; docs/exchange.md).

The FMU carries the model file and a small Python slave; at each step the slave sets
the inputs on the model's ports and solves (:class:`~powergraph.exchange.fmu_runtime.
TrainStepper`). pythonfmu FMUs run Python code: the machine that runs the FMU needs
Python (the version the FMU was built with, as a shared library) with powergraph
installed.

Examples
--------
>>> print(SLAVE.splitlines()[0])
# A powergraph train as an FMI 2.0 co-simulation slave (powergraph export --to fmu).
"""
from __future__ import annotations

import shutil
import tempfile
from pathlib import Path

from powergraph.errors import UsageError

#: The slave script pythonfmu builds into the FMU; it reads the model from the FMU's
#: resources (``model`` plus the file's suffix).
SLAVE = '''# A powergraph train as an FMI 2.0 co-simulation slave (powergraph export --to fmu).
from pathlib import Path

from pythonfmu import Fmi2Causality, Fmi2Slave, Real


class PowerGraphTrain(Fmi2Slave):
    author = "powergraph"
    description = "Power flow, losses and efficiency of a gear train (powergraph)"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        from powergraph.exchange.fmu_runtime import TrainStepper

        model = next(p for p in Path(self.resources).iterdir() if p.stem == "model")
        self.stepper = TrainStepper(str(model))
        values = self.stepper.values
        for name in self.stepper.inputs:
            self.register_variable(Real(
                name, causality=Fmi2Causality.input, start=values[name],
                getter=lambda n=name: values[n],
                setter=lambda v, n=name: values.__setitem__(n, v)))
        for name in self.stepper.outputs:
            self.register_variable(Real(name, causality=Fmi2Causality.output,
                                        getter=lambda n=name: values[n]))

    def do_step(self, current_time, step_size):
        self.stepper.step()
        return True
'''


def build_fmu(model_path: str | Path, target: str | Path) -> Path:
    """Build ``target`` (``.fmu``) from the model file at ``model_path``.

    Raises
    ------
    UsageError
        When pythonfmu is not installed.
    """
    try:
        from pythonfmu.builder import FmuBuilder
    except ImportError:
        raise UsageError('--to fmu needs pythonfmu: pip install -e ".[fmu]" (or pip install '
                         'pythonfmu)') from None
    from powergraph.exchange.fmu_runtime import TrainStepper

    source, target = Path(model_path), Path(target)
    TrainStepper(str(source))               # the model must solve before it is packed
    with tempfile.TemporaryDirectory(prefix="powergraph_fmu_") as folder:
        script = Path(folder) / "powergraph_train.py"
        script.write_text(SLAVE, encoding="utf-8")
        model = Path(folder) / f"model{source.suffix.lower()}"
        shutil.copyfile(source, model)
        built = FmuBuilder.build_FMU(script, dest=folder, project_files=[model])
        shutil.move(str(built), target)
    return target
