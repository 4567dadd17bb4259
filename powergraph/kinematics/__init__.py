"""Kinematics layer: bodies' speeds from Willis' relations (docs/theory.md)."""
from __future__ import annotations

from powergraph.kinematics.elements import Element, element_stencil, elements_of, willis_ratio
from powergraph.kinematics.variants import backdriven
from powergraph.kinematics.speeds import (
    Kinematics,
    constraint_matrix,
    degrees_of_freedom,
    solve_speeds,
)

__all__ = ["Element", "Kinematics", "backdriven", "constraint_matrix", "degrees_of_freedom",
           "element_stencil", "elements_of", "solve_speeds", "willis_ratio"]
