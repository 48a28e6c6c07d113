"""``Sessions`` and ``ControlLease``: who an operator is, and how long they hold control.

An operator is a session the server issued (``POST /api/session`` with the token): a secret
id the page sends back with each request, and a public name the others see. No header a
client picks names anyone. Control is a lease held by one session: taking it starts the
lease, the page's heartbeat renews it, and it lapses ``seconds`` after the last renewal
(a page closed, reloaded or crashed stops renewing); the page also gives it back on
``pagehide``. Both read an injected clock (wall time by default), so tests step time
instead of sleeping.
"""

from __future__ import annotations

import secrets
import threading
import time
from collections import OrderedDict
from collections.abc import Callable
from dataclasses import dataclass

from homebot.errors import ConsoleError

__all__ = ["ControlLease", "Session", "Sessions"]


@dataclass
class Session:
    """One page's session: its public name and when it was last heard from."""

    name: str
    seen: float


class Sessions:
    """The live sessions, at most ``limit`` (the longest silent is forgotten first), each
    forgotten after ``idle`` seconds without a request."""

    def __init__(self, *, idle: float = 600.0, limit: int = 64,
                 clock: Callable[[], float] = time.monotonic) -> None:
        self.idle = idle
        self.limit = limit
        self._clock = clock
        self._live: OrderedDict[str, Session] = OrderedDict()
        self._lock = threading.Lock()
        self._issued = 0

    def open(self, *, keep: str | None = None) -> tuple[str, str]:
        """A new session: (its secret id, its public name). When ``limit`` are live, the
        longest silent is forgotten, never the one named ``keep`` (who holds control)."""
        with self._lock:
            self._forget_idle()
            while len(self._live) >= max(self.limit, 2):
                oldest = next(secret for secret, session in self._live.items()
                              if session.name != keep)
                del self._live[oldest]
            self._issued += 1
            secret = secrets.token_urlsafe(24)
            name = f"operator-{self._issued}-{secrets.token_hex(2)}"
            self._live[secret] = Session(name, self._clock())
            return secret, name

    def name(self, secret: str | None) -> str | None:
        """The public name of the live session ``secret`` (and it counts as heard from now),
        or None for no such session."""
        if not secret:
            return None
        with self._lock:
            self._forget_idle()
            key = next((known for known in self._live
                        if secrets.compare_digest(known.encode(), secret.encode())), None)
            if key is None:
                return None
            self._live.move_to_end(key)
            found = self._live[key]
            found.seen = self._clock()
            return found.name

    def close(self, secret: str | None) -> str | None:
        """End the session ``secret``; its public name, or None when there was none."""
        name = self.name(secret)
        if name is not None and secret is not None:
            with self._lock:
                self._live.pop(secret, None)
        return name

    def __len__(self) -> int:
        with self._lock:
            self._forget_idle()
            return len(self._live)

    def _forget_idle(self) -> None:
        now = self._clock()
        while self._live:
            oldest = next(iter(self._live.values()))
            if now - oldest.seen <= self.idle:
                break
            self._live.popitem(last=False)


class ControlLease:
    """Control of the robot: held by one operator until released or ``seconds`` without a
    renewal have passed. It has a lock of its own: a page's heartbeat never waits for the
    robot (the console's lock is held while the robot thinks, seconds on a loaded machine,
    and a renewal that waited that long would find the lease lapsed)."""

    def __init__(self, seconds: float, *, clock: Callable[[], float] = time.monotonic) -> None:
        if not seconds > 0:
            raise ConsoleError(f"a control lease of {seconds} s: give a number of seconds "
                               "above 0")
        self.seconds = seconds
        self._clock = clock
        self._holder: str | None = None
        self._until = 0.0
        self._lock = threading.RLock()

    @property
    def holder(self) -> str | None:
        """Who holds control now (None: nobody, or the lease lapsed)."""
        with self._lock:
            if self._holder is not None and self._clock() > self._until:
                self._holder = None
            return self._holder

    def left(self) -> float:
        """Seconds until the lease lapses without a renewal (0 when nobody holds it)."""
        with self._lock:
            return max(0.0, self._until - self._clock()) if self.holder is not None else 0.0

    def take(self, operator: str) -> None:
        """``operator`` takes control (or renews it); refused while another holds it."""
        with self._lock:
            if self.holder not in (None, operator):
                raise ConsoleError("another operator holds control; watch, or wait until "
                                   "they release it (it lapses when their page goes away)")
            self._holder, self._until = operator, self._clock() + self.seconds

    def renew(self, operator: str) -> bool:
        """Renew ``operator``'s lease; False when they do not hold it (any more)."""
        with self._lock:
            if self.holder != operator:
                return False
            self._until = self._clock() + self.seconds
            return True

    def release(self, operator: str) -> None:
        """``operator`` gives control back (nothing happens when they do not hold it)."""
        with self._lock:
            if self.holder == operator:
                self._holder = None
