"""The material library: production-style procedural materials shipped as Substance ``.sbs`` files.

Each material is written in Python in ``sources/<name>.py`` (the authoring contract: a module
docstring, ``build() -> SbsGraph``,
``FAMILY`` (a key of ``catalog.FAMILIES``), ``SAMPLE_RANGES`` and optionally ``SAMPLE_TOGETHER``,
the listed colours drawn as a line rather than channel by channel), exported by
``python -m blender_match.library.build`` to ``graphs/<name>.sbs`` (the Substance document) and
``graphs/<name>.json`` (metadata: node and parameter counts, exposed parameters, sampling ranges
keyed by the parameter names of the graph as ``load_sbs_graph`` returns it). At run time only the
shipped files are read: a library graph is the translation of its ``.sbs`` file.

A user library folder of the same layout (``blender-match library add``, ``library.user``) is
searched together with the shipped one; see ``catalog``.

API: ``library_names()`` (``builtin_names()`` + ``user_names()``), ``library_entry(name)``,
``load_library_graph(name)``,
``sample_params(name, k)`` (the k-th random variant, in the parameter-file format of
``diffmat.params_file``), ``source_names()`` and ``build_source(name)`` (the Python sources).
The catalogue (``catalog``: names, metadata, variants) and this package import without torch,
so that the Blender add-on reads the library with the same code; loading a graph needs torch.
"""
from __future__ import annotations

import importlib
import pkgutil

from . import sources
from .catalog import (
    FAMILIES,
    GRAPHS_DIR,
    LIBRARY_DIR,
    MODELS_DIR,
    LibraryError,
    builtin_names,
    library_entry,
    library_names,
    library_path,
    metadata_file,
    models_folder,
    sample_params,
    thumbnail_file,
    user_library_dir,
    user_names,
)


def source_names() -> list[str]:
    """Names of the material sources (modules of ``blender_match.library.sources``)."""
    return sorted(m.name for m in pkgutil.iter_modules(sources.__path__) if not m.name.startswith("_"))


def source_module(name: str):
    if name not in source_names():
        raise LibraryError(f"{name}: no material source named so (sources: {', '.join(source_names())})")
    return importlib.import_module(f"{__name__}.sources.{name}")


def build_source(name: str):
    """The SbsGraph a source module builds (its name must be the module's)."""
    graph = source_module(name).build()
    if graph.name != name:
        raise LibraryError(f"sources/{name}.py: build() returns a graph named {graph.name!r}, expected {name!r}")
    return graph


def load_library_graph(name: str, mode: str = "exposed_plus"):
    """The SbsGraph of a library material: the translation of its shipped ``.sbs`` file."""
    # torch loads here, not at the top: the catalogue (and so this package) must import without it
    from ..translator import load_sbs_graph

    entry = library_entry(name)
    graph = load_sbs_graph(entry["path"], entry.get("graph"), mode=mode)
    graph.name = name  # a user file's graph keeps its own identifier in the package; reports use the library's
    return graph


def apply_params(graph, params: dict):
    """Set a graph's parameters from a {"node.param": value} dict (checked like a parameter file)."""
    from ..diffmat.params_file import apply_params as apply_checked  # torch: see load_library_graph

    apply_checked(graph, params, f"graph {graph.name}")


__all__ = ["FAMILIES", "GRAPHS_DIR", "LIBRARY_DIR", "MODELS_DIR", "LibraryError", "apply_params", "build_source",
           "builtin_names", "library_entry", "library_names", "library_path", "load_library_graph", "metadata_file",
           "models_folder", "sample_params", "source_module", "source_names", "thumbnail_file", "user_library_dir",
           "user_names"]
