"""What the worker job and the backend setup share: both are polled from Blender's main thread
(``poll()`` returns the new events, ``done`` says when a terminal one has come); scripts and tests
block on them with ``wait``. Standard library only."""
from __future__ import annotations

import time
from abc import ABC, abstractmethod


class Polled(ABC):
    """Mix-in: ``wait`` for classes with ``poll() -> list[dict]`` and a ``done`` property."""

    @abstractmethod
    def poll(self) -> list[dict]:
        """The events that came since the last call."""

    @property
    @abstractmethod
    def done(self) -> bool:
        """Whether a terminal event has come."""

    def wait(self, timeout: float | None = None, interval: float = 0.05) -> list[dict]:
        """Poll until done (or ``timeout`` seconds); all events seen. For scripts, the command line
        and tests; the add-on polls from a timer instead."""
        deadline = None if timeout is None else time.monotonic() + timeout
        events: list[dict] = []
        while True:
            events += self.poll()
            if self.done or (deadline is not None and time.monotonic() > deadline):
                return events
            time.sleep(interval)
