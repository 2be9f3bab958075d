"""Exceptions raised by frictionsim: the ground floor of the package (this module imports nothing of it).

The C++ engine's exceptions arrive as these classes (translated in bindings/results.cpp):

* :class:`InvalidParameterError` (a :class:`ValueError`): bad input; ``parameter`` names it.
* :class:`SimulationError`: the integration stopped before ``t_end``; ``time_reached`` [s] is the last time the
  solution is valid and ``partial`` holds the :class:`frictionsim.Result` recorded up to it.
* :class:`ChatteringError`: more switches than the chattering bound allows (Zeno behaviour);
  ``switching_function`` names the guard.
* :class:`BudgetExceededError`: a budget of the run ran out (``budget`` names it: ``"timeout"``,
  ``"max_output_rows"``, ``"max_output_bytes"``); the partial result is kept like any stop.
* :class:`AccuracyWarning`: a completed result that may be unreliable (a tolerance too loose for its error
  estimate to mean anything); ``Result.warnings`` keeps the text.

Ctrl-C during a run raises ``KeyboardInterrupt`` (never a SimulationError), and so does a ``KeyboardInterrupt`` or
``SystemExit`` raised inside a Python callable the rig calls: they propagate unchanged.
"""

from __future__ import annotations

from typing import Any

__all__ = ["InvalidParameterError", "SimulationError", "ChatteringError", "BudgetExceededError", "AccuracyWarning"]


class InvalidParameterError(ValueError):
    """A parameter breaks a physical rule; ``parameter`` names it and the message states the rule."""

    def __init__(self, message: str, parameter: str) -> None:
        super().__init__(message)
        self.parameter = parameter

    def __reduce__(self):  # picklable, so errors cross process pools intact
        return (type(self), (str(self), self.parameter))


class SimulationError(RuntimeError):
    """The run stopped early. ``time_reached`` [s]; ``partial`` is the Result up to it (or None)."""

    def __init__(self, message: str, time_reached: float, partial: Any = None) -> None:
        super().__init__(message)
        self.time_reached = float(time_reached)
        #: The results recorded up to ``time_reached`` as a :class:`frictionsim.Result` (the engine's translator
        #: makes it), or None.
        self.partial = partial

    def __reduce__(self):
        return (type(self), (str(self), self.time_reached, self.partial))


class ChatteringError(SimulationError):
    """Too many switches within the event window; ``switching_function`` names the guard."""

    def __init__(self, message: str, time_reached: float, partial: Any = None, switching_function: str = "") -> None:
        super().__init__(message, time_reached, partial)
        self.switching_function = switching_function

    def __reduce__(self):
        return (type(self), (str(self), self.time_reached, self.partial, self.switching_function))


class BudgetExceededError(SimulationError):
    """A budget of the run ran out; ``budget`` names the option (``"timeout"``, ``"max_output_rows"``,
    ``"max_output_bytes"``)."""

    def __init__(self, message: str, time_reached: float, partial: Any = None, budget: str = "") -> None:
        super().__init__(message, time_reached, partial)
        self.budget = budget

    def __reduce__(self):
        return (type(self), (str(self), self.time_reached, self.partial, self.budget))


class AccuracyWarning(UserWarning):
    """A completed result that may be unreliable, e.g. simulated at a tolerance looser than its error estimate
    can vouch for."""
