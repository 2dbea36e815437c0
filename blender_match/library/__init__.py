"""The material library: production-style procedural materials shipped as Substance ``.sbs`` files.

Each material is written in Python in ``sources/<name>.py`` (the authoring contract: a module
docstring, ``build() -> SbsGraph`` and ``SAMPLE_RANGES``), exported by
``python -m blender_match.library.build`` to ``graphs/<name>.sbs`` (the Substance document) and
``graphs/<name>.json`` (metadata: node and parameter counts, exposed parameters, sampling ranges
keyed by the parameter names of the graph as ``load_sbs_graph`` returns it). At run time only the
shipped files are read: a library graph is the translation of its ``.sbs`` file.

API: ``library_names()``, ``library_entry(name)``, ``load_library_graph(name)``,
``sample_params(name, k)`` (the k-th random variant, in the parameter-file format of
``diffmat.params_file``), ``source_names()`` and ``build_source(name)`` (the Python sources).
"""
from __future__ import annotations

import importlib
import json
import pkgutil
import random
import re
from pathlib import Path

from ..diffmat.errors import DiffMatError

LIBRARY_DIR = Path(__file__).resolve().parent
GRAPHS_DIR = LIBRARY_DIR / "graphs"
_NAME = re.compile(r"^[a-z][a-z0-9_]*$")


def source_names() -> list[str]:
    """Names of the material sources (modules of ``blender_match.library.sources``)."""
    from . import sources

    return sorted(m.name for m in pkgutil.iter_modules(sources.__path__) if not m.name.startswith("_"))


def source_module(name: str):
    if name not in source_names():
        raise DiffMatError(f"{name}: no material source named so (sources: {', '.join(source_names())})")
    return importlib.import_module(f"{__name__}.sources.{name}")


def build_source(name: str):
    """The SbsGraph a source module builds (its name must be the module's)."""
    graph = source_module(name).build()
    if graph.name != name:
        raise DiffMatError(f"sources/{name}.py: build() returns a graph named {graph.name!r}, expected {name!r}")
    return graph


def library_names() -> list[str]:
    """Names of the shipped library graphs (``graphs/*.json`` with their ``.sbs``)."""
    if not GRAPHS_DIR.is_dir():
        return []
    return sorted(p.stem for p in GRAPHS_DIR.glob("*.json") if (GRAPHS_DIR / f"{p.stem}.sbs").is_file())


def _check(name: str) -> str:
    if not isinstance(name, str) or not _NAME.match(name) or name not in library_names():
        known = ", ".join(library_names()) or "none"
        raise DiffMatError(f"{name}: not a library graph (library: {known})")
    return name


def library_entry(name: str) -> dict:
    """The metadata of a library graph: name, file, description, nodes, params_optimizable,
    exposed, sample_ranges ({"node.param": [lo, hi]}, names as in the translated graph)..."""
    _check(name)
    entry = json.loads((GRAPHS_DIR / f"{name}.json").read_text(encoding="utf-8"))
    entry["path"] = str(GRAPHS_DIR / entry["file"])
    return entry


def library_path(name: str) -> Path:
    return GRAPHS_DIR / f"{_check(name)}.sbs"


def load_library_graph(name: str, mode: str = "exposed_plus"):
    """The SbsGraph of a library material: the translation of its shipped ``.sbs`` file."""
    from ..translator import load_sbs_graph

    return load_sbs_graph(library_path(name), mode=mode)


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
        raise DiffMatError(f"{name}: sample index must be a non-negative integer, got {k!r}")
    rng = random.Random(f"{name}/{k}")
    return {key: _draw(rng, lo, hi) for key, (lo, hi) in sorted(entry["sample_ranges"].items())}


def apply_params(graph, params: dict):
    """Set a graph's parameters from a {"node.param": value} dict (checked like a parameter file)."""
    from ..diffmat.params_file import apply_params as _apply

    _apply(graph, params, f"graph {graph.name}")


__all__ = ["library_names", "library_entry", "load_library_graph", "sample_params", "source_names",
           "build_source", "library_path", "apply_params", "GRAPHS_DIR"]
