"""The user's own library: ``.sbs`` materials added to the folder that ``catalog.user_library_dir``
names, searched by automatic matching together with the shipped graphs.

An entry ``NAME`` is three things in ``graphs/``: ``NAME/`` (a copy of the added ``.sbs`` and of
the local files it depends on, at the same relative paths, so the entry keeps working when the
original moves), ``NAME.png`` (its thumbnail) and ``NAME.json`` (its metadata, written last: an
entry is listed only once its metadata exists, so an interrupted add leaves nothing half-listed).
Its selection models go to the library's ``models/`` (built by the pipeline, which knows them).

``add_entry`` refuses, with a one-line ``LibraryError`` naming the file, what cannot be rendered: a
file the translator cannot read, a dependency outside the file's folder, a graph whose render is
not finite. Parameters are sampled for the bank around the authored value (``build.default_spread``:
15% of each parameter's range, less for a value small on its scale), as for a shipped graph
without declared ranges.
"""
from __future__ import annotations

import hashlib
import json
import re
import shutil
import tempfile
from pathlib import Path

import torch

from ..diffmat.errors import DiffMatError
from ..image_files import write_png
from ..safe_files import write_json_atomic
from ..translator import TranslatorError, load_sbs_graph, local_dependencies
from .build import graph_summary, sample_ranges
from .catalog import NAME, LibraryError, builtin_names, user_library_dir, user_names
from .thumbnails import flash_render


def entry_name(path: Path) -> str:
    """The library name a file gets by default: its stem in lower case, every run of other
    characters than letters and digits made one ``_``, prefixed with ``m_`` when it does not start
    with a letter (``Rust Brown-02.sbs`` -> ``rust_brown_02``)."""
    name = re.sub(r"[^a-z0-9]+", "_", Path(path).stem.lower()).strip("_")
    return name if NAME.match(name) else f"m_{name}".rstrip("_")


def file_sha256(path: Path) -> str:
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def check_new_name(name: str, overwrite: bool) -> None:
    if not NAME.match(name):
        raise LibraryError(f"{name}: not a valid library name (lower-case letters, digits and _, starting "
                           "with a letter)")
    if name in builtin_names():
        raise LibraryError(f"{name}: a built-in graph has that name; choose another with --name")
    if name in user_names() and not overwrite:
        raise LibraryError(f"{name}: already in the user library ({user_library_dir()}); "
                           "use --overwrite to replace it or --name to add it under another name")


def user_entry(name: str) -> dict | None:
    """The metadata of user entry ``name`` (None when there is none or it cannot be read)."""
    path = user_library_dir() / "graphs" / f"{name}.json"
    try:
        entry = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, json.JSONDecodeError):
        return None
    return entry if isinstance(entry, dict) else None


def _copy_package(sbs: Path, folder: Path) -> None:
    """Copy ``sbs`` and its local dependencies (at their relative paths) into ``folder``."""
    base = sbs.parent
    for relative in local_dependencies(sbs):
        if relative.startswith("..") or Path(relative).is_absolute():
            raise LibraryError(f"{sbs}: depends on {relative}, outside the file's folder; put it beside the file")
        source = base / relative
        if source.is_file():
            (folder / relative).parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(source, folder / relative)
    shutil.copyfile(sbs, folder / sbs.name)


def _checked_thumbnail(graph, sbs: Path) -> torch.Tensor:
    """The graph's flash render at its defaults, thumbnail-sized, clamped to [0, 1];
    LibraryError when it cannot be rendered or is not finite."""
    if not graph.outputs:
        raise LibraryError(f"{sbs}: the graph has no material output")
    try:
        image = flash_render(graph)
    except (DiffMatError, RuntimeError, ValueError) as exc:
        raise LibraryError(f"{sbs}: cannot be rendered ({exc})") from None
    if not bool(torch.isfinite(image).all()):
        raise LibraryError(f"{sbs}: its render has values that are not finite")
    return image.clamp(0, 1)


def add_entry(sbs, name: str | None = None, graph_name: str | None = None, overwrite: bool = False,
              measure=None) -> dict:
    """Add one graph of the .sbs file ``sbs`` (its material graph unless ``graph_name``) to the
    user library as ``name`` (default ``entry_name(sbs)``); its metadata (as ``library_entry``
    reads it), with what ``measure(graph)`` returns (a dict) when given: the layers above record
    what they measure of the graph in the same write. LibraryError, naming the file, when it
    cannot be added; the library is unchanged then."""
    sbs = Path(sbs).expanduser().resolve()
    if not sbs.is_file():
        raise LibraryError(f"{sbs}: no such file")
    if sbs.suffix.lower() != ".sbs":
        raise LibraryError(f"{sbs}: not a Substance .sbs file")
    name = name or entry_name(sbs)
    check_new_name(name, overwrite)
    try:
        graph = load_sbs_graph(sbs, graph_name)
    except TranslatorError as exc:
        raise LibraryError(str(exc)) from None
    thumbnail = _checked_thumbnail(graph, sbs)
    report = graph.report
    meta = {"name": name, "file": f"{name}/{sbs.name}", "description": f"{report['graph']} from {sbs.name}",
            "graph": report["graph"], "origin": str(sbs), "sha256": file_sha256(sbs),
            "nodes_passthrough": report["nodes_passthrough"], **graph_summary(graph),
            **sample_ranges(graph, {}, {}, name), **(measure(graph) if measure is not None else {})}
    graphs = user_library_dir() / "graphs"
    graphs.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(dir=graphs, prefix=f".adding-{name}-") as tmp:
        staged = Path(tmp) / name
        staged.mkdir()
        _copy_package(sbs, staged)
        remove_entry(name, missing_ok=True)
        staged.rename(graphs / name)
    write_png(graphs / f"{name}.png", thumbnail, overwrite=True)
    write_json_atomic(graphs / f"{name}.json", meta, overwrite=True)
    return meta


def remove_entry(name: str, missing_ok: bool = False) -> list[Path]:
    """Remove user entry ``name``: its metadata first (so it is no longer listed), then its
    thumbnail, its files and its models; the paths removed. Built-in graphs cannot be removed."""
    if name in builtin_names():
        raise LibraryError(f"{name}: a built-in graph; only graphs of the user library can be removed")
    root = user_library_dir()
    graphs = root / "graphs"
    if not (graphs / f"{name}.json").is_file() and not (graphs / name).is_dir() and not missing_ok:
        raise LibraryError(f"{name}: not in the user library ({root})")
    removed = []
    for path in (graphs / f"{name}.json", graphs / f"{name}.png", *sorted((root / "models").glob(f"{name}.*"))):
        if path.is_file():
            path.unlink()
            removed.append(path)
    if (graphs / name).is_dir():
        shutil.rmtree(graphs / name)
        removed.append(graphs / name)
    return removed
