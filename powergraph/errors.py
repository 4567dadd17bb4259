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

from powergraph.records import record


class PowerGraphError(Exception):
    """Root of every error powergraph raises on purpose.

    Parameters
    ----------
    message : str
        What is wrong, in the user's terms.
    path : str, optional
        Where in the model file it is wrong (``links[2].carrier``), if anywhere.
    missing : {"speed", "load"}, optional
        The model gives too few values of this kind (a speed, or a power or torque) to
        determine the train: a caller that left some out (a duty cycle's empty cells)
        can name them.
    """

    def __init__(self, message: str, path: str | None = None,
                 missing: str | None = None) -> None:
        self.message = message
        self.path = path
        self.missing = missing
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


@record
class Caveat:
    """A warning about a model or a result: the answer stands, but a designer should know.

    Not an exception: models and results carry them in ``warnings`` (a tuple), the text
    reports print them as ``warning: PATH: MESSAGE`` lines, ``--json`` lists them as
    strings, and ``--strict`` turns them into errors (exit 2).

    Parameters
    ----------
    message : str
        What is doubtful, in the user's terms, with what to write instead when there is
        something to write.
    path : str, optional
        The place in the model file (``ports[1]``, ``links[0]``), naming the port's or
        link's name where it has one.
    code : str
        A short stable kind (``bare-speed``, ``role-reversed``, ``coaxiality``...) that
        tests and scripts can filter on.

    Examples
    --------
    >>> str(Caveat("read as 1500 rad/s; write '1500 rad/s' or '1500 rpm'",
    ...            "ports[0].speed", "bare-speed"))
    "ports[0].speed: read as 1500 rad/s; write '1500 rad/s' or '1500 rpm'"
    """

    message: str
    path: str | None = None
    code: str = "warning"

    def __str__(self) -> str:
        return f"{self.path}: {self.message}" if self.path else self.message

    def to_error(self) -> "ModelError":
        """The same text as a :class:`ModelError` (what ``--strict`` raises)."""
        return ModelError(self.message, self.path)
