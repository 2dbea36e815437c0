"""The progress bars of ``blender-match match`` and ``train``: on stderr when it is a terminal,
with the stage, the fit's iteration and loss, and the training phase; nothing otherwise."""
from __future__ import annotations

import io

import pytest

from blender_match.cli.match import _MatchProgress
from blender_match.cli.train import _TrainingProgress


class _Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


MATCH_EVENTS = [{"stage": "reading photo", "fraction": 0.0, "eta_seconds": None},
                {"stage": "fitting", "fraction": 0.5, "eta_seconds": 12.0, "iteration": 5, "iterations": 10,
                 "loss": 0.25}]
TRAIN_EVENTS = [{"phase": "data", "done": 4, "total": 4}, {"phase": "fit", "done": 10, "total": 20, "val_error": 0.125}]


def _shown(monkeypatch, stderr, display, events) -> str:
    monkeypatch.setattr("sys.stderr", stderr)
    bar = display()
    bar.bar.mininterval = 0  # draw every event
    for event in events:
        bar(event)
    bar.close()
    return stderr.getvalue()


def test_match_progress_on_a_terminal(monkeypatch):
    shown = _shown(monkeypatch, _Terminal(), _MatchProgress, MATCH_EVENTS)
    assert "fitting" in shown and "50.0%" in shown
    assert "iteration 5/10  loss 0.25000" in shown and "12 s left" in shown


def test_training_progress_on_a_terminal(monkeypatch):
    shown = _shown(monkeypatch, _Terminal(), lambda: _TrainingProgress("plaster"), TRAIN_EVENTS)
    assert "plaster data" in shown and "4/4" in shown
    assert "plaster fit" in shown and "10/20" in shown and "val error 0.1250" in shown


@pytest.mark.parametrize("display, events", [(_MatchProgress, MATCH_EVENTS),
                                             (lambda: _TrainingProgress("plaster"), TRAIN_EVENTS)])
def test_no_progress_when_stderr_is_not_a_terminal(monkeypatch, display, events):
    assert _shown(monkeypatch, io.StringIO(), display, events) == ""
