"""The library's catalogue: which graphs there are, their metadata, and the random variants their
declared parameter ranges allow.

Two libraries are searched together. The built-in one is shipped in the package
(``library/graphs/<name>.json`` beside its ``.sbs``, models in ``library/models/``). The user's
own (``blender-match library add``) lives in a folder of the same layout: ``graphs/<name>.json``,
``graphs/<name>.png`` and the entry's ``.sbs`` under ``graphs/<name>/`` (with the local files it
depends on), models in ``models/``. That folder is ``$BLENDER_MATCH_LIBRARY`` when it is set (the
add-on sets it from its preferences), else the platform's user-data folder
(``user_library_dir``). A built-in name always wins: a user entry of the same name is not listed.

Standard library only: the Blender add-on (whose Python has no torch) lists and describes the
library graphs with these functions, as the command line and the pipeline do.
"""
from __future__ import annotations

import json
import os
import random
import re
import sys
from pathlib import Path

from ..errors import BlenderMatchError

LIBRARY_DIR = Path(__file__).resolve().parent
GRAPHS_DIR = LIBRARY_DIR / "graphs"
MODELS_DIR = LIBRARY_DIR / "models"
USER_LIBRARY_ENV = "BLENDER_MATCH_LIBRARY"
NAME = re.compile(r"^[a-z][a-z0-9_]*$")
BUILT_IN, USER = "built-in", "user"
FAMILIES = {
    "fabric": "Fabric",
    "leather": "Leather",
    "metal": "Metal",
    "stone": "Stone",
    "plaster": "Plaster & concrete",
    "wood": "Wood",
    "tile": "Tile & brick",
    "coating": "Paint & coating",
    "ground": "Ground & other",
}
"""Material families (key: label), in the order the add-on's graph picker shows them. A library
source declares its family (``FAMILY``); a user entry has none (the picker files it under its
library's label)."""


class LibraryError(BlenderMatchError):
    """A name that is not a library graph or source, or library metadata that cannot be read."""


def user_library_dir() -> Path:
    """The user library's folder: ``$BLENDER_MATCH_LIBRARY``, else ``blender_match/library`` in
    the platform's user-data folder (``%APPDATA%`` on Windows, ``~/Library/Application Support`` on
    macOS, ``$XDG_DATA_HOME`` or ``~/.local/share`` elsewhere). It need not exist yet."""
    chosen = os.environ.get(USER_LIBRARY_ENV, "").strip()
    if chosen:
        return Path(chosen).expanduser()
    if sys.platform == "win32":
        base = Path(os.environ.get("APPDATA") or Path.home() / "AppData" / "Roaming")
    elif sys.platform == "darwin":
        base = Path.home() / "Library" / "Application Support"
    else:
        base = Path(os.environ.get("XDG_DATA_HOME") or Path.home() / ".local" / "share")
    return base / "blender_match" / "library"


def _names_in(graphs_dir: Path) -> list[str]:
    """Names of the entries of a ``graphs/`` folder: ``<name>.json`` files with their ``<name>.sbs``
    (built-in) or their ``<name>/`` folder (user entries)."""
    if not graphs_dir.is_dir():
        return []
    return [meta.stem for meta in sorted(graphs_dir.glob("*.json"))
            if NAME.match(meta.stem) and ((graphs_dir / f"{meta.stem}.sbs").is_file()
                                          or (graphs_dir / meta.stem).is_dir())]


def builtin_names() -> list[str]:
    """Names of the shipped library graphs (``graphs/*.json`` with their ``.sbs``)."""
    return _names_in(GRAPHS_DIR)


def user_names() -> list[str]:
    """Names of the user library's graphs, built-in names excepted."""
    taken = set(builtin_names())
    return [n for n in _names_in(user_library_dir() / "graphs") if n not in taken]


def library_names() -> list[str]:
    """Every graph automatic matching searches: the built-in ones, then the user's."""
    return builtin_names() + user_names()


def family_of(entry: dict) -> str | None:
    """The family (a key of FAMILIES) of a library entry, None for a user entry or an unknown one."""
    family = entry.get("family")
    return family if entry.get("library") != USER and family in FAMILIES else None


def by_family(names: list[str]) -> list[str]:
    """Library graph names grouped by family in FAMILIES' order, then the user's, each group sorted."""
    order = {key: i for i, key in enumerate(FAMILIES)}
    return sorted(names, key=lambda n: (order.get(family_of(library_entry(n)) or "", len(order)), n))


def check_name(name: str) -> str:
    """``name`` when it names a library graph, else LibraryError listing the library."""
    if not isinstance(name, str) or not NAME.match(name) or name not in library_names():
        known = ", ".join(library_names()) or "none"
        raise LibraryError(f"{name}: not a library graph (library: {known})")
    return name


def library_root(name: str) -> Path:
    """The folder of the library holding graph ``name`` (with its ``graphs/`` and ``models/``)."""
    if name in builtin_names():  # most lookups: one listing of the shipped folder
        return LIBRARY_DIR
    check_name(name)
    return user_library_dir()


def models_folder(name: str) -> Path:
    """Where graph ``name``'s selection models (bank, predictor) live."""
    return MODELS_DIR if library_root(name) == LIBRARY_DIR else user_library_dir() / "models"


def metadata_file(name: str) -> Path:
    """Graph ``name``'s metadata file (``graphs/<name>.json`` of its library)."""
    return library_root(name) / "graphs" / f"{name}.json"


def library_entry(name: str) -> dict:
    """The metadata of a library graph: name, file, description, nodes, params_optimizable,
    exposed, exposed_params, sample_ranges ({"node.param": [lo, hi]}, names as in the translated
    graph)... plus "path", its .sbs file, and "library", BUILT_IN or USER. A user entry also has
    "graph" (the graph's identifier in its package) and "origin" (the file it was added from)."""
    path = metadata_file(name)
    root = path.parent.parent
    try:
        entry = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise LibraryError(f"{path}: unreadable ({exc})") from None
    if not isinstance(entry, dict):
        raise LibraryError(f"{path}: not a JSON object")
    graphs = (root / "graphs").resolve()
    sbs = (graphs / str(entry.get("file", f"{name}.sbs"))).resolve()
    if graphs not in sbs.parents:
        raise LibraryError(f"{path}: its file {entry.get('file')!r} lies outside {graphs}")
    entry["path"] = str(sbs)
    entry["library"] = BUILT_IN if root == LIBRARY_DIR else USER
    return entry


def library_path(name: str) -> Path:
    """The .sbs file of library graph ``name``."""
    return Path(library_entry(name)["path"])


def thumbnail_file(name: str) -> Path:
    """Where graph ``name``'s thumbnail is (``graphs/<name>.png`` of its library; may be absent)."""
    return library_root(name) / "graphs" / f"{name}.png"


def _draw(rng: random.Random, lo, hi, together: bool = False):
    if isinstance(lo, list):
        if together:
            t = rng.random()
            return [round(a + t * (b - a), 6) for a, b in zip(lo, hi)]
        return [round(rng.uniform(a, b), 6) for a, b in zip(lo, hi)]
    return round(rng.uniform(lo, hi), 6)


def sample_params(name: str, k: int) -> dict:
    """The k-th random variant of a library graph: every optimisable parameter drawn uniformly in
    its declared range (the components of a ``sample_together`` vector with one shared fraction of
    their ranges), seeded by (name, k); ``{"node.param": value or [values]}`` (exposed
    parameters as ``exposed.NAME``), as the "params" of a parameter file."""
    entry = library_entry(name)
    if isinstance(k, bool) or not isinstance(k, int) or k < 0:
        raise LibraryError(f"{name}: sample index must be a non-negative integer, got {k!r}")
    rng = random.Random(f"{name}/{k}")
    together = set(entry.get("sample_together", ()))
    return {key: _draw(rng, lo, hi, key in together) for key, (lo, hi) in sorted(entry["sample_ranges"].items())}
