"""The translator's one exception type."""
from __future__ import annotations

import os

from ..errors import BlenderMatchError

MAX_MESSAGE = 300


class TranslatorError(BlenderMatchError):
    """A .sbs document the translator cannot (or will not) translate: one line naming the file and
    the problem."""

    def __init__(self, path, problem: str):
        name = os.fspath(path) if isinstance(path, (str, os.PathLike)) else str(path)
        text = " ".join(str(problem).split())
        if len(text) > MAX_MESSAGE:
            text = text[:MAX_MESSAGE] + "..."
        super().__init__(f"{name}: {text}")
        self.path = name
        self.problem = text
