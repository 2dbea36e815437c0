"""Writing files safely: atomically (a temporary file and a rename, so that a reader never sees a
half-written file) and never over an existing file unless the caller says so."""
from __future__ import annotations

import json
import os
import tempfile
from pathlib import Path

from .errors import BlenderMatchError


class FileWriteError(BlenderMatchError):
    """A file that may not or cannot be written (names the file and the problem)."""


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def write_atomic(path: Path, data: bytes, overwrite: bool = False):
    """Write ``data`` to ``path`` through a temporary file and a rename, so that a reader never
    sees a half-written file. Refuses to replace an existing file unless ``overwrite``."""
    path = Path(path)
    if path.exists() and not overwrite:
        raise FileWriteError(f"{path}: already exists (pass an overwrite option to replace it)")
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.chmod(tmp, 0o666 & ~_umask())  # mkstemp's 0600 would hide the file from other users
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def json_text(data, default=None) -> str:
    """The text of every JSON file the project writes: ``data`` indented by one, ending in a
    newline (``default`` as ``json.dumps`` takes it)."""
    return json.dumps(data, indent=1, default=default) + "\n"


def write_json_atomic(path: Path, data, overwrite: bool = False, default=None):
    """``json_text(data)`` written by ``write_atomic``."""
    write_atomic(path, json_text(data, default).encode("utf-8"), overwrite=overwrite)
