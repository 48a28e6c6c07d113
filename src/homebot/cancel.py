"""``CancelToken``: a request to stop a run, made by whoever watches it, checked by what runs.

The console's stop button, a ROS node's goal cancel or a person's "stop" cancel the token;
the executive (between steps), the skills (between attempts and in their long loops) and
the robot's long motions check it and end with a clear outcome. Nothing is raised.
"""

from __future__ import annotations

__all__ = ["CancelToken"]


class CancelToken:
    """One run's cancel request: once cancelled it stays so; a new run takes a new token.

    Cancelling is one assignment, so a watcher's thread may cancel while the run's
    thread checks.
    """

    def __init__(self) -> None:
        self._reason: str | None = None

    def cancel(self, reason: str = "cancelled") -> None:
        """Ask the run to stop, saying why; the first reason given is the one kept."""
        if self._reason is None:
            self._reason = reason

    @property
    def cancelled(self) -> bool:
        """Whether the run was asked to stop."""
        return self._reason is not None

    @property
    def reason(self) -> str:
        """Why the run was asked to stop ("" while it was not)."""
        return self._reason or ""

    def __repr__(self) -> str:
        return f"CancelToken(cancelled: {self._reason!r})" if self.cancelled else \
            "CancelToken()"
