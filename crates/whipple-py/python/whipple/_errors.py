"""whipple's exceptions and warnings.

Every error of the Rust library reaches Python as one of these classes (never as a panic), with
the offending ``field`` (as the user wrote it: ``'mB'``, ``'lean'``, ``'dt'``), its ``value``
where there is one, and the ``rule`` it breaks, in words.
"""

from __future__ import annotations

from typing import Any, Optional


class WhippleError(Exception):
    """Base class of every whipple error; ``field``, ``value``, ``rule`` describe it."""

    field: Optional[str]
    value: Any
    rule: Optional[str]

    def __init__(self, message: str, *, field: Optional[str] = None, value: Any = None,
                 rule: Optional[str] = None, **extra: Any) -> None:
        super().__init__(message)
        self.field = field
        self.value = value
        self.rule = rule
        for key, item in extra.items():
            setattr(self, key, item)


class ParameterError(WhippleError, ValueError):
    """A parameter (or a combination, ``field`` then lists them) breaks a rule of the model:
    non-finite, negative mass, a mass matrix that is not positive definite, an unknown key."""


class StrictError(ParameterError):
    """``strict=True`` was asked for and the bicycle has warnings (``value`` is their count)."""


class ParseError(WhippleError, ValueError):
    """A parameter file could not be read; also ``format``, ``line`` and ``column`` (1-based,
    0 when unknown)."""

    format: str
    line: int
    column: int


class UnknownPresetError(WhippleError, LookupError):
    """No preset of that name (``value``); ``rule`` lists the known ones."""


class ArgumentError(WhippleError, ValueError):
    """A speed, range, step, torque or other argument is unusable (``field`` names it)."""


class LimitError(ArgumentError):
    """A request asks for more work than a bound allows (for example more integration steps)."""


class NumericalError(WhippleError, ArithmeticError):
    """A numerical method failed: no convergence, a non-finite result, singular equations."""


class NoSteadyTurnError(WhippleError, ValueError):
    """No steady turn with what was asked for (``given``, in words; ``rule`` says why): the
    solver, started from straight running, could not reach one, or it leaves the region where
    the model is defined. ``field`` names the argument held (``'lean'``, ``'steer'``,
    ``'radius'``) when :meth:`whipple.Bicycle.turn` raises it."""

    given: str


class AccuracyLostError(NumericalError):
    """Double precision cannot give this answer to the accuracy it would be printed with
    (``field`` names the quantity, ``rule`` why)."""


class ParameterWarning(UserWarning):
    """A measured bicycle's oddity that keeps the equations well defined (a tensor that breaks
    the triangle inequality, a centre of mass below the ground); ``strict=True`` refuses it."""


__all__ = [
    "WhippleError", "ParameterError", "StrictError", "ParseError", "UnknownPresetError",
    "ArgumentError", "LimitError", "NumericalError", "AccuracyLostError",
    "NoSteadyTurnError", "ParameterWarning",
]
