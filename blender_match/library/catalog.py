"""The library's catalogue: which graphs are shipped (``graphs/<name>.json`` with its ``.sbs``),
their metadata, and the random variants their declared parameter ranges allow.

Standard library only: the Blender add-on (whose Python has no torch) lists and describes the
library graphs with these functions, as the command line and the pipeline do.
"""
from __future__ import annotations

import json
import random
import re
from pathlib import Path

from ..errors import BlenderMatchError

LIBRARY_DIR = Path(__file__).resolve().parent
GRAPHS_DIR = LIBRARY_DIR / "graphs"
NAME = re.compile(r"^[a-z][a-z0-9_]*$")


class LibraryError(BlenderMatchError):
    """A name that is not a library graph or source, or library metadata that cannot be read."""


def library_names() -> list[str]:
    """Names of the shipped library graphs (``graphs/*.json`` with their ``.sbs``)."""
    if not GRAPHS_DIR.is_dir():
        return []
    return sorted(p.stem for p in GRAPHS_DIR.glob("*.json") if (GRAPHS_DIR / f"{p.stem}.sbs").is_file())


def check_name(name: str) -> str:
    """``name`` when it names a library graph, else LibraryError listing the library."""
    if not isinstance(name, str) or not NAME.match(name) or name not in library_names():
        known = ", ".join(library_names()) or "none"
        raise LibraryError(f"{name}: not a library graph (library: {known})")
    return name


def library_entry(name: str) -> dict:
    """The metadata of a library graph: name, file, description, nodes, params_optimizable,
    exposed, exposed_params, sample_ranges ({"node.param": [lo, hi]}, names as in the translated
    graph)... plus "path", its .sbs file."""
    path = GRAPHS_DIR / f"{check_name(name)}.json"
    try:
        entry = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise LibraryError(f"{path}: unreadable ({exc})") from None
    if not isinstance(entry, dict):
        raise LibraryError(f"{path}: not a JSON object")
    entry["path"] = str(GRAPHS_DIR / entry.get("file", f"{name}.sbs"))
    return entry


def library_path(name: str) -> Path:
    return GRAPHS_DIR / f"{check_name(name)}.sbs"


def _draw(rng: random.Random, lo, hi):
    if isinstance(lo, list):
        return [round(rng.uniform(a, b), 6) for a, b in zip(lo, hi)]
    return round(rng.uniform(lo, hi), 6)


def sample_params(name: str, k: int) -> dict:
    """The k-th random variant of a library graph: every optimisable parameter drawn uniformly in
    its declared range, seeded by (name, k); ``{"node.param": value or [values]}`` (exposed
    parameters as ``exposed.NAME``), as the "params" of a parameter file."""
    entry = library_entry(name)
    if isinstance(k, bool) or not isinstance(k, int) or k < 0:
        raise LibraryError(f"{name}: sample index must be a non-negative integer, got {k!r}")
    rng = random.Random(f"{name}/{k}")
    return {key: _draw(rng, lo, hi) for key, (lo, hi) in sorted(entry["sample_ranges"].items())}
