"""Bringing the user's own ``.sbs`` materials into automatic matching: ``add_sbs`` adds a file's
material graph to the user library (``library.user``) and builds its selection entry, the sample
bank (``selection.bank``), so that ``match`` without ``--graph`` ranks it beside the shipped graphs.

Resumable: a file already in the library unchanged (same name, same SHA-256) is not translated
again, and its bank is built only when it is missing or stale, so an interrupted run over a folder,
started again, picks up at the first file not done. A bank is written whole, never half: the
graph's own defaults and 64 samples. The defaults are the look the file's author made; the samples
move every optimisable parameter at once (±15% of its range around its authored value), and over
hundreds of parameters they can all land far from it (docs/matching.md). The parameter predictor,
a longer training, is left to ``blender-match train --graph NAME``; the bank alone ranks a graph
and proposes its start. A new graph's size dependence is measured as it is added: a graph that
looks different at 128 px than at a match's 512 brought down is rendered that finely for its bank
and its ranking (``selection.bank.measured_supersample``); an entry added before this was measured
is added again.
"""
from __future__ import annotations

import time
from pathlib import Path

from ..library import LibraryError
from ..library.user import add_entry, entry_name, file_sha256, user_entry
from ..selection.bank import SUPERSAMPLE_KEY, bank_is_current, build_bank, measured_supersample
from ..selection.descriptor import DESCRIPTOR_SIZE
from .options import PHOTO_SIZE


def bank_batch(device) -> int:
    """Bank samples rendered at once on ``device``: one on a CPU, where a batch of eight saves at
    most a quarter of the time and can triple the peak memory of a large production graph (a
    laptop adding a folder overnight must not run out of it; docs/matching.md); eight elsewhere."""
    return 1 if str(device).split(":")[0] == "cpu" else 8


def _measure(device):
    """What ``add_entry`` records of a new graph: how finely selection renders it
    (``selection.bank.measured_supersample``, against a match's own size)."""
    factor = PHOTO_SIZE // DESCRIPTOR_SIZE
    return lambda graph: {SUPERSAMPLE_KEY: measured_supersample(graph.to(device), factor, device)}


def sbs_files(path) -> list[Path]:
    """``path`` when it is a file; the ``.sbs`` files under it, at any depth and sorted, when it is
    a folder (hidden folders skipped)."""
    path = Path(path).expanduser()
    if path.is_dir():
        return sorted(p for p in path.rglob("*.sbs")
                      if p.is_file() and not any(part.startswith(".") for part in p.relative_to(path).parts))
    if not path.exists():
        raise LibraryError(f"{path}: no such file or folder")
    return [path]


def add_sbs(sbs, *, name: str | None = None, graph_name: str | None = None, overwrite: bool = False,
            device="cpu", progress=None) -> dict:
    """Add ``sbs`` to the user library and build its bank; {"name", "status" ("added", "up to date"
    or "bank rebuilt"), "nodes", "params", "passthrough", "supersample" (``selection.bank``),
    "seconds"}. ``progress(done, total)`` follows the bank's
    samples. LibraryError (one line naming the file) when it cannot be added."""
    start = time.perf_counter()
    sbs = Path(sbs).expanduser().resolve()
    name = name or entry_name(sbs)
    entry = user_entry(name)
    same = (entry is not None and sbs.is_file() and entry.get("sha256") == file_sha256(sbs)
            and graph_name in (None, entry.get("graph")))
    if entry is not None and same and not overwrite and SUPERSAMPLE_KEY in entry:
        status = "up to date" if bank_is_current(name) else "bank rebuilt"
    else:  # new, replaced, or added by a version that did not measure the graph's size dependence
        entry = add_entry(sbs, name, graph_name, overwrite=overwrite or same, measure=_measure(device))
        status = "added"
    if status != "up to date":
        build_bank(name, device=device, progress=progress, batch=bank_batch(device), with_defaults=True)
    return {"name": name, "status": status, "nodes": entry["nodes"], "params": entry["params_optimizable"],
            "passthrough": entry.get("nodes_passthrough", 0), "supersample": entry.get(SUPERSAMPLE_KEY, 1),
            "seconds": time.perf_counter() - start}
