"""The exceptions of the chaplygin package."""

from __future__ import annotations

from typing import Optional

import numpy


class ChaplyginError(Exception):
    """The base of the package's exceptions."""


class ModelError(ChaplyginError):
    """A model the compiler rejects.

    ``str(error)`` lists every diagnostic as ``file:line:column: error: ...``
    with the offending source line; ``line``, ``column`` (both from 1) and
    ``message`` are the first diagnostic's.
    """

    def __init__(self, text: str, line: int, column: int, message: str) -> None:
        super().__init__(text)
        self.line = line
        self.column = column
        self.message = message


class SimulationError(ChaplyginError):
    """A run that stopped before its end: a singular configuration, the
    model's domain ending, a non-finite state, a failed step.

    ``t`` is the time it stopped at and ``state`` the state that caused it
    (``None`` where the failure has none); ``trajectory`` holds the rows
    recorded before it.
    """

    def __init__(
        self,
        message: str,
        t: Optional[float],
        state: Optional[numpy.ndarray],
        trajectory: "Optional[object]" = None,
    ) -> None:
        super().__init__(message)
        self.message = message
        self.t = t
        self.state = state
        self.trajectory = trajectory
