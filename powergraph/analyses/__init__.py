"""Analyses beyond power flow (docs/architecture.md): backlash (Li et al. 2012,
docs/backlash.md), cycloid fluctuation (Csobán 2021, docs/cycloid.md), volume (Pan & Wang
2019, docs/volume.md), compiled sweeps (docs/sweep.md), closed-form formulas
(docs/formula.md), tolerances (docs/tolerance.md), efficiency maps (docs/losses.md) and the
comparison of trains."""
