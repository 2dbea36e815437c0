"""``blender-match bench ranking``: automatic selection alone, on real photos, in seconds a photo.

Automatic matching keeps the ranking's first graph (``pipeline.AUTO_CANDIDATES``), so whether a
photo gets a material of its family is settled before any fit. ``bench photos --quick`` measures
it with the fits (about half a minute a photo); this suite runs only the selection
(``selection.rank_graphs`` on the photo as ``match`` reads it, ``load_photo`` at ``PHOTO_SIZE``,
graph seed ``photos.SEED``), a few seconds a photo, so that a change to the ranking can be
judged on every photo in minutes. Its ``first`` is the graph ``bench photos`` keeps with one
candidate.

By default it reads both real-photo folders, ``../shared/data/photos_dev`` and the bundled
photos beside it (``--photos DIR``: that folder alone); categories and families as ``bench
photos`` gives them (``photos.photo_category``, ``photo_categories.json``). Per photo: the
category, the ranking's first and first three, ``family_rank`` (the place of the first graph of
the photo's family in the ranking, 1 = first; none when the selection index's shortlist left the
family out), the seconds. The summary: the share of photos whose family comes first (the family
match of ``bench photos``), in the top 3, ranked at all. With ``out``: ``results.json`` (the
rows with every ranked graph's distance and start) and ``results.md``.
"""
from __future__ import annotations

import math
import sys
import time
from pathlib import Path
from typing import Any

from ..photo import load_photo
from ..pipeline import PHOTO_SIZE, resolve_device
from ..selection import rank_graphs, shared_vgg
from .accuracy_targets import photos_dir
from .markdown import table
from .photos import (
    SEED,
    default_photos,
    find_photos,
    listed_categories,
    load_families,
    load_photo_labels,
    photo_category,
)
from .results_files import write_json_and_markdown

COLUMNS = ("photo", "category", "first", "top3", "family_rank", "seconds", "error")


def family_rank(ranking: list[dict], family) -> int | None:
    """1-based place of the first graph of ``family`` in the ranking; None when none is ranked."""
    return next((i + 1 for i, e in enumerate(ranking) if e["graph"] in family), None)


def summarise(rows: list[dict], seconds: float) -> dict:
    """Photos, and the share whose family is ranked first, in the first three, ranked at all (in
    the shortlist; a failed photo counts as a miss everywhere), total seconds."""
    ranks = [r["family_rank"] for r in rows]

    def share(limit: float) -> float:
        return round(sum(k is not None and k <= limit for k in ranks) / len(rows), 3)

    return {"photos": len(rows), "failed": sum(bool(r["error"]) for r in rows), "family_first": share(1),
            "family_top3": share(3), "family_ranked": share(math.inf), "total_seconds": round(seconds, 1)}


def run(device: str = "cpu", photos=None, out: Path | None = None) -> list[dict]:
    """Rank the library for every photo (module docstring): the per-photo rows then the "all"
    row; [] with one line on stderr when no folder holds a photo."""
    folders = [Path(photos)] if photos is not None else [default_photos(), photos_dir()]
    paths = [p for folder in folders for p in find_photos(folder)]
    if not paths:
        print(f"bench ranking: no photos (*.jpg, *.jpeg, *.png) in {', '.join(map(str, folders))}: nothing to "
              "measure (--photos DIR names another folder)", file=sys.stderr)
        return []
    families, labels = load_families(), load_photo_labels()
    listed = {folder: listed_categories(folder) for folder in folders}
    torch_device = resolve_device(device)
    shared_vgg(torch_device)  # loaded once, before the clock of the first photo starts
    rows = []
    started = time.perf_counter()
    for index, path in enumerate(paths):
        category, _ = photo_category(path, families, listed[path.parent], labels)
        row: dict[str, Any] = {"photo": path.name, "category": category, "first": "", "top3": [],
                               "family_rank": None, "seconds": None, "error": "", "ranking": []}
        try:
            begun = time.perf_counter()
            ranking = rank_graphs(load_photo(path, PHOTO_SIZE).to(torch_device), "both", seed=SEED,
                                  device=torch_device)
            row |= {"seconds": round(time.perf_counter() - begun, 2), "first": ranking[0]["graph"],
                    "top3": [e["graph"] for e in ranking[:3]],
                    "family_rank": family_rank(ranking, families.get(category, ())),
                    "ranking": [{"graph": e["graph"], "distance": round(e["distance"], 6), "start": e["start"]}
                                for e in ranking]}
        except Exception as exc:  # noqa: BLE001 - one photo's failure is its row's, not the run's
            row["error"] = f"{type(exc).__name__}: {exc}"
        rows.append(row)
        print(f"[{time.perf_counter() - started:5.0f}s] {index + 1}/{len(paths)} {path.name} ({category}): "
              + (row["error"] or f"{', '.join(row['top3'])}; family at {row['family_rank']}"), file=sys.stderr,
              flush=True)
    summary = summarise(rows, time.perf_counter() - started)
    if out is not None:
        config = {"photos_dirs": [str(f) for f in folders], "seed": SEED, "photo_size": PHOTO_SIZE,
                  "device": str(torch_device)}
        write_json_and_markdown(out, {"config": config, "rows": rows, "summary": summary}, "\n\n".join(
            ["# bench ranking", table([summary], list(summary)), "## Per photo", table(rows, COLUMNS)]))
    return [{c: r[c] for c in COLUMNS} | {"top3": ", ".join(r["top3"])} for r in rows] + [
        {"photo": "all", "category": f"{summary['photos']} photos", "first": f"{summary['family_first']:.0%}",
         "top3": f"{summary['family_top3']:.0%} in the top 3", "family_rank":
         f"{summary['family_ranked']:.0%} ranked", "seconds": "", "error": f"{summary['failed']} failed"}]
