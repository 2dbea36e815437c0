"""Job-wide progress: stage-local progress turned into events with the fraction of the whole job
and the time left, and the cancel flag polled between steps."""
from __future__ import annotations

import time
from collections.abc import Callable

from ..errors import Cancelled
from ..vocabulary import FITTING, READING_PHOTO, SELECTING, WRITING_MAPS

# Share of the whole job each stage takes, for the progress fraction: with a named graph, and with
# automatic selection (ranking the library's 16 graphs takes about 5% of a balanced auto match).
NAMED_SHARES = {READING_PHOTO: 0.02, FITTING: 0.88, WRITING_MAPS: 0.10}
AUTO_SHARES = {READING_PHOTO: 0.02, SELECTING: 0.05, FITTING: 0.83, WRITING_MAPS: 0.10}
RENDER_SHARES = {WRITING_MAPS: 1.0}


class JobProgress:
    """Turns stage-local progress into job-wide events (fraction of the whole, time left) sent to
    ``callback``; ``check_cancel`` raises ``Cancelled`` once ``cancel()`` returns True."""

    def __init__(self, callback: Callable[[dict], None] | None, cancel: Callable[[], bool] | None,
                 shares: dict[str, float]):
        self.callback, self.cancel, self.shares = callback, cancel, shares
        self.start = time.perf_counter()
        self.stage_seconds: dict[str, float] = {}
        self._stage: str | None = None
        self._stage_start, self._done = self.start, 0.0

    def stage(self, name: str | None, **extra) -> None:
        """End the current stage and start ``name`` (None: the job is done)."""
        now = time.perf_counter()
        if self._stage is not None:
            self.stage_seconds[self._stage] = round(now - self._stage_start, 3)
            self._done += self.shares[self._stage]
        self._stage, self._stage_start = name, now
        if name is not None:
            self.check_cancel()
            self.emit({"stage": name, "fraction": round(self._done, 4), "eta_seconds": None, **extra})

    def within(self, local_fraction: float, eta_seconds: float | None = None, **extra) -> None:
        """Progress inside the current stage: ``local_fraction`` of it is done."""
        assert self._stage is not None, "within() outside a stage"
        share = self.shares[self._stage]
        self.emit({"stage": self._stage, "fraction": round(self._done + share * min(1.0, local_fraction), 4),
                   "eta_seconds": None if eta_seconds is None else round(eta_seconds, 1), **extra})

    def emit(self, event: dict) -> None:
        if self.callback is not None:
            self.callback(event)

    def check_cancel(self) -> None:
        if self.cancel is not None and self.cancel():
            raise Cancelled()

    def seconds(self) -> float:
        return round(time.perf_counter() - self.start, 3)
