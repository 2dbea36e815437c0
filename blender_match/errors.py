"""The two exceptions every floor of the package shares (standard library only: the Blender
add-on imports this without torch).

``BlenderMatchError`` is the root of every error a user can act on: a bad photo, option, file,
graph or parameter. Its message is one line naming the thing and the problem, and the command
line and the worker show it as it is. Anything that is not a ``BlenderMatchError`` (nor an
``OSError`` from the file system) is a bug, reported with its traceback.

``Cancelled`` is the one way a job stops because its caller's cancel flag was set (a fit, the
selection, a predictor's training, a whole match): it is an outcome, not an error, so it does
not derive from ``BlenderMatchError`` and an ``except BlenderMatchError`` never swallows it.
"""
from __future__ import annotations


class BlenderMatchError(Exception):
    """Something the user can fix; the message names the file, option or value and the problem."""


class OptionError(BlenderMatchError):
    """An option or argument outside what it accepts (size, quality, device, k, a sub-command's
    arguments)."""


class Cancelled(Exception):
    """The caller's cancel flag stopped the job; the job wrote nothing it was asked to write
    (a training checkpoint keeps what was done)."""


class ResultFolderError(BlenderMatchError):
    """A result folder (or its params.json / report.json) that cannot be used: names the folder or
    file and the problem. The pipeline writes result folders and the add-on reads them."""
