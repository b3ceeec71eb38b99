"""The one exception the robot library raises for bad input (unknown name, bad URDF)."""

from __future__ import annotations

from rmot.lang.diagnostics import Code

__all__ = ["RobotError"]


class RobotError(Exception):
    """A message fit to show users, and the diagnostic code it belongs to."""

    def __init__(self, message: str, code: Code | None = None) -> None:
        super().__init__(message)
        self.message = message
        self.code = code
