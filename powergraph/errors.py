"""The one error hierarchy of powergraph.

Every error the package raises on purpose derives from :class:`PowerGraphError`;
each subclass is also the builtin a Python user would expect (like pint's errors),
so ``except ValueError`` keeps working.

Examples
--------
>>> from powergraph.errors import ModelError
>>> err = ModelError("unknown component 'c9'", path="links[2].carrier")
>>> str(err)
"links[2].carrier: unknown component 'c9'"
>>> isinstance(err, ValueError)
True
"""
from __future__ import annotations


class PowerGraphError(Exception):
    """Root of every error powergraph raises on purpose.

    Parameters
    ----------
    message : str
        What is wrong, in the user's terms.
    path : str, optional
        Where in the model file it is wrong (``links[2].carrier``), if anywhere.
    """

    def __init__(self, message: str, path: str | None = None) -> None:
        self.message = message
        self.path = path
        super().__init__(f"{path}: {message}" if path else message)


class ModelError(PowerGraphError, ValueError):
    """The model file (or a model built in Python) is invalid."""


class KinematicsError(ModelError):
    """The train's speeds cannot be determined (wrong DOF, contradictory speeds...)."""


class StaticsError(ModelError):
    """The torques cannot be determined (missing or contradictory loads)."""


class SolveError(PowerGraphError, RuntimeError):
    """A numerical procedure failed (e.g. power directions did not settle)."""


class MethodNotApplicableError(ModelError):
    """A paper's method was asked for on a train it does not describe."""


class UsageError(PowerGraphError, ValueError):
    """Bad command-line or function arguments (not a model problem)."""
