"""``blender-match bench photos``: automatic matching on every photo of a folder of real photos.

What a user gets from ``blender-match match PHOTO`` without ``--graph``, on photos that have no
ground truth. Each photo (every ``*.jpg``, ``*.jpeg`` and ``*.png`` of the folder, sorted; by
default ``../shared/data/photos_dev``, never part of the project) is read as ``match`` reads it
(``load_photo`` at ``PHOTO_SIZE``) and goes through the product's automatic path
(``pipeline.fit_photo``, ``match`` without writing: every library graph ranked by its predicted
start, the top ``pipeline.AUTO_CANDIDATES`` fitted, the best kept; graph seed
``SEED``). Per photo the row gives:

- ``graph`` (the kept graph), ``top3`` (the ranking's first three) and
  ``family_match``: whether the kept graph belongs to the photo's category's family in
  ``photo_categories.json`` (the table says per category which graphs count, and why; a category
  with an empty family, or one not in the table, is one the library cannot express: always a miss);
- ``ranking`` and ``fitted`` (results.json only): the ranking's entries and each fitted
  candidate's summary, as report.json gives them, so that the final choice can be studied;
- ``seconds``: wall time of selection and fitting (the photo's reading, the render below and the
  maps ``match`` writes afterwards are not part of it);
- ``loss``: the kept fit's final descriptor loss, the quantity the fit minimises;
- ``patch_distance`` and ``colour_distance`` (``image_distances``: yardsticks no fit minimises)
  between the photo and the kept material rendered as ``comparison.png`` shows it: at
  ``PHOTO_SIZE`` with the fit's seed, framed at its zoom, under the photo's flash as the fit
  solved it (``Match.camera``); ``patch_distance_ideal_flash`` the same under the ideal flash, so
  that what the material itself gained is told apart from what the solved light gained;
- ``calibration``: the zoom, the gain and the falloff, as report.json gives them.

A photo's category is the one the table's ``photos`` section gives it by name (photos whose
listed category names a condition or nothing, labelled by looking at them, each with its reason),
else the first attribute of its line in the folder's ``SOURCES.tsv`` (columns ``file`` and
``attributes``; ``-`` means misc) or, without one, the first ``_``-separated word of its name that
is a category of the table (``real_asphalt_gravel_desch18.png``: asphalt), else its first word. A
photo that fails (unreadable, a fit error) gets its error in its row, counts as a miss and the run
goes on. The summary: photos, the share of family matches, the same share by the listed categories
alone (``family_match_share_listed``: a relabelled photo's match counts as a miss there), the
medians of the two distances and of the seconds, the total seconds. With ``out``: ``results.json`` (config, rows,
summary), ``results.md`` (the tables; the photos themselves never go into it) and ``sheet.png``
(per photo: photo | render | the kept graph, category and match). ``quick``: the draft preset;
``candidates``: how many of the ranking's graphs each match fits (``MatchOptions.candidates``).
"""
from __future__ import annotations

import csv
import io
import json
import statistics
import sys
import textwrap
import time
from pathlib import Path
from typing import Any

import numpy as np
import torch
from PIL import Image, ImageDraw

from ..diffmat.calibration import framed_maps
from ..diffmat.optim import resize_square
from ..diffmat.render import render_maps
from ..errors import OptionError
from ..photo import load_photo
from ..pipeline import AUTO_CANDIDATES, PHOTO_SIZE, MatchOptions, fit_photo, resolve_device
from ..safe_files import write_atomic
from ..selection import shared_vgg
from ..vocabulary import QUALITY_NAMES
from .accuracy_targets import photos_dir
from .image_distances import colour_distance, patch_distance
from .markdown import table
from .results_files import write_json_and_markdown

CATEGORIES_FILE = Path(__file__).with_name("photo_categories.json")
SUFFIXES = (".jpg", ".jpeg", ".png")
MISC = "misc"
SEED = 0
TILE = 192
COLUMNS = ("photo", "category", "graph", "top3", "family_match", "seconds", "loss", "patch_distance",
           "colour_distance", "error")


def default_photos() -> Path:
    """``photos_dev`` beside the bundled real photos in shared/ (``BLENDER_MATCH_SHARED`` honoured)."""
    return photos_dir().parent / "photos_dev"


def read_table(path: Path = CATEGORIES_FILE) -> dict:
    """The category table's JSON object (OptionError naming the file when it is unreadable)."""
    try:
        table = json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        raise OptionError(f"{path}: not a photo category table ({exc})") from None
    if not isinstance(table, dict):
        raise OptionError(f"{path}: not a photo category table (not a JSON object)")
    return table


def load_families(path: Path = CATEGORIES_FILE) -> dict[str, list[str]]:
    """Category -> the library graphs that count as its family."""
    try:
        return {category: list(entry["graphs"]) for category, entry in read_table(path)["categories"].items()}
    except (KeyError, TypeError, AttributeError) as exc:
        raise OptionError(f"{path}: not a photo category table ({exc})") from None


def load_photo_labels(path: Path = CATEGORIES_FILE) -> dict[str, str]:
    """Photo file name -> the category the table gives it where its listed category names no
    material (``photos`` of the table: judged by looking at the photo, with the reason)."""
    try:
        return {name: entry["category"] for name, entry in read_table(path).get("photos", {}).items()}
    except (KeyError, TypeError, AttributeError) as exc:
        raise OptionError(f"{path}: not a photo category table ({exc})") from None


def find_photos(folder: Path) -> list[Path]:
    """The folder's photos, sorted; [] when it is absent."""
    if not folder.is_dir():
        return []
    return sorted(p for p in folder.iterdir() if p.is_file() and p.suffix.lower() in SUFFIXES)


def listed_categories(folder: Path) -> dict[str, str]:
    """File name -> main category (first of ``attributes``, ``-`` -> misc) from the folder's
    SOURCES.tsv; {} when it has none or no such columns (the bundled set lists no attributes)."""
    path = folder / "SOURCES.tsv"
    if not path.is_file():
        return {}
    with path.open(newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f, delimiter="\t", quoting=csv.QUOTE_NONE)
        if not {"file", "attributes"} <= set(reader.fieldnames or ()):
            return {}
        out = {}
        for line in reader:
            main = (line["attributes"] or "").split(",")[0].strip().lower()
            out[line["file"]] = MISC if main in ("", "-") else main
    return out


def name_category(stem: str, known) -> str:
    """The first ``_``-separated word of ``stem`` that is a ``known`` category, else its first word."""
    words = stem.lower().split("_")
    return next((w for w in words if w in known), words[0])


def photo_category(path: Path, families, listed: dict[str, str], labels: dict[str, str]) -> tuple[str, str]:
    """(category, listed category) of the photo at ``path``: the table's label (``labels``), else
    its folder's ``SOURCES.tsv`` attribute (``listed``), else a word of its name; the listed
    category is the same without the label."""
    listed_category = listed.get(path.name) or name_category(path.stem, families)
    return labels.get(path.name) or listed_category, listed_category


def evaluate(photo: torch.Tensor, options: MatchOptions) -> tuple[dict, torch.Tensor]:
    """Automatic selection and fitting of ``photo`` (1, 3, S, S) as ``match`` without ``--graph``
    does (``pipeline.fit_photo``): the row's measured fields and the kept material's flash render
    (1, 3, S, S)."""
    started = time.perf_counter()
    match = fit_photo(photo, options)
    seconds = time.perf_counter() - started
    with torch.no_grad():
        maps = framed_maps(match.graph, photo.shape[-1], options.seed)
        render = render_maps(maps, match.camera)[:1].clamp(0, 1).cpu()
        ideal = render_maps(maps)[:1].clamp(0, 1).cpu()
    return {"graph": match.graph.name, "top3": [e["graph"] for e in match.report["ranking"][:3]],
            "seconds": round(seconds, 2), "loss": match.report["loss_final"],
            "patch_distance": patch_distance(photo, render), "colour_distance": colour_distance(photo, render),
            "patch_distance_ideal_flash": patch_distance(photo, ideal),
            "ranking": match.report["ranking"], "fitted": match.report["fitted"],
            "calibration": match.report["calibration"]}, render


def summarise(rows: list[dict], seconds: float, listed_misses: int = 0) -> dict:
    """Photos, share of family matches (a failed photo is a miss), the same share with the
    ``listed_misses`` matches the table's photo labels made counted as misses (the photo's
    listed category names no material), medians over the photos that were fitted, total
    seconds of the run."""
    done = [r for r in rows if not r["error"]]
    matches = sum(r["family_match"] for r in rows)

    def median(key):
        return round(statistics.median(r[key] for r in done), 3) if done else None

    return {"photos": len(rows), "failed": len(rows) - len(done),
            "family_match_share": round(matches / len(rows), 3),
            "family_match_share_listed": round((matches - listed_misses) / len(rows), 3),
            "median_patch_distance": median("patch_distance"), "median_colour_distance": median("colour_distance"),
            "median_patch_distance_ideal_flash": median("patch_distance_ideal_flash"),
            "median_seconds": median("seconds"), "total_seconds": round(seconds, 1)}


def summary_row(summary: dict) -> dict:
    """The summary in the per-photo columns, for the printed table's last row ("all")."""
    return {"photo": "all", "category": f"{summary['photos']} photos", "graph": "", "top3": "",
            "family_match": f"{summary['family_match_share']:.0%}", "seconds": summary["median_seconds"],
            "loss": "", "patch_distance": summary["median_patch_distance"],
            "colour_distance": summary["median_colour_distance"],
            "error": f"{summary['failed']} failed; total {summary['total_seconds']:.0f} s"}


def markdown(rows: list[dict], summary: dict, config: dict) -> str:
    return "\n\n".join([
        "# bench photos",
        f"{config['photos_dir']}: quality {config['quality']}"
        + (f", {config['iterations']} iterations" if config["iterations"] else "")
        + f", top {config['k']} fitted, zoom {config['zoom']}, "
        + ("the photo's flash solved" if config["lighting"] else "the ideal flash")
        + f", seed {SEED}, photo size {config['photo_size']} px, "
        f"device {config['device']}, "
        f"torch threads {config['threads']}. family match: the kept graph is in the category's family "
        "(photo_categories.json); distances: photo against the kept material's render under the photo's solved "
        "flash (patch_distance_ideal_flash: under the ideal flash; lower is closer); "
        "seconds: selection and fitting; medians over the photos that did not fail",
        table([summary], list(summary)), "## Per photo", table(rows, COLUMNS)]) + "\n"


def _tile(image: torch.Tensor | None):
    """A TILE-px PIL tile of a (1, 3, S, S) image in [0, 1]; dark grey when there is none."""
    if image is None:
        return Image.new("RGB", (TILE, TILE), (48, 48, 48))
    small = resize_square(image.float().cpu(), TILE)[0].clamp(0, 1)
    return Image.fromarray(np.rint(small.permute(1, 2, 0).numpy() * 255).astype(np.uint8))


def _label(row: dict):
    """The third tile of a sheet row: the kept graph (or the error), category and match."""
    tile = Image.new("RGB", (TILE, TILE), (24, 24, 24))
    draw = ImageDraw.Draw(tile)
    if row["error"]:
        lines = ["FAILED", *textwrap.wrap(row["error"], 30)[:8]]
    else:
        lines = [row["graph"], "", f"category: {row['category']}",
                 "in its family" if row["family_match"] else "not in its family", "",
                 f"patch {row['patch_distance']:.1f}  colour {row['colour_distance']:.1f}",
                 f"{row['seconds']:.0f} s", "", *textwrap.wrap(row["photo"], 30)]
    colour = (120, 220, 120) if row["family_match"] else (240, 140, 120)
    for i, text in enumerate(lines):
        draw.text((8, 8 + 14 * i), text, fill=colour if i == 0 else (230, 230, 230))
    return tile


def sheet_png(entries: list[tuple]) -> bytes:
    """PNG bytes of the sheet: per (photo, render, row), photo | render | label, TILE px each."""
    sheet = Image.new("RGB", (3 * TILE, len(entries) * TILE), (0, 0, 0))
    for i, (photo, render, row) in enumerate(entries):
        for j, tile in enumerate((_tile(photo), _tile(render), _label(row))):
            sheet.paste(tile, (j * TILE, i * TILE))
    buffer = io.BytesIO()
    sheet.save(buffer, "PNG")
    return buffer.getvalue()


def run(device: str = "cpu", photos=None, quick: bool = False, quality: str | None = None, out: Path | None = None,
        limit: int | None = None, iterations: int | None = None, candidates: int = AUTO_CANDIDATES,
        zoom: float | None = 1.0, lighting: bool = True) -> list[dict]:
    """Match every photo of ``photos`` (module docstring): the per-photo rows then the "all" row;
    [] with one line on stderr when the folder holds no photo. ``limit``: the first photos only."""
    quality = quality or ("draft" if quick else "balanced")
    if quality not in QUALITY_NAMES:
        raise OptionError(f"quality {quality!r}: expected one of {', '.join(QUALITY_NAMES)}")
    folder = Path(photos) if photos is not None else default_photos()
    paths = find_photos(folder)[:limit]
    if not paths:
        print(f"bench photos: no photos (*.jpg, *.jpeg, *.png) in {folder}: nothing to measure "
              "(--photos DIR names another folder)", file=sys.stderr)
        return []
    families = load_families()
    listed = listed_categories(folder)
    labels = load_photo_labels()
    torch_device = resolve_device(device)
    options = MatchOptions(quality=quality, seed=SEED, device=device, iterations=iterations, candidates=candidates,
                           zoom=zoom, lighting=lighting)
    shared_vgg(torch_device)  # loaded once, before the clock of the first photo starts
    rows, entries, listed_misses = [], [], 0
    started = time.perf_counter()
    for index, path in enumerate(paths):
        category, listed_category = photo_category(path, families, listed, labels)
        row: dict[str, Any] = {c: None for c in COLUMNS} | {"photo": path.name, "category": category, "graph": "",
                                                            "top3": [], "family_match": False, "error": ""}
        photo = render = None
        try:
            photo = load_photo(path, PHOTO_SIZE)
            fields, render = evaluate(photo, options)
            row |= fields | {"family_match": fields["graph"] in families.get(category, ())}
        except Exception as exc:  # noqa: BLE001 - one photo's failure is its row's, not the run's
            row["error"] = f"{type(exc).__name__}: {exc}"
        rows.append(row)
        entries.append((photo, render, row))
        listed_misses += row["family_match"] and row["graph"] not in families.get(listed_category, ())
        done = (f"kept {row['graph']} ({'match' if row['family_match'] else 'miss'}), top3 {', '.join(row['top3'])}, "
                f"patch {row['patch_distance']:.1f}, colour {row['colour_distance']:.1f}, {row['seconds']:.0f}s"
                if not row["error"] else f"FAILED: {row['error']}")
        print(f"[{time.perf_counter() - started:6.0f}s] {index + 1}/{len(paths)} {path.name} ({category}): {done}",
              file=sys.stderr, flush=True)
    summary = summarise(rows, time.perf_counter() - started, listed_misses)
    if out is not None:
        out = Path(out)
        config = {"photos_dir": str(folder), "quality": quality, "iterations": iterations, "k": options.candidates,
                  "seed": SEED, "zoom": "auto" if zoom is None else zoom, "lighting": lighting,
                  "photo_size": PHOTO_SIZE, "device": str(torch_device), "threads": torch.get_num_threads(),
                  "categories": {c: families.get(c, []) for c in sorted({r["category"] for r in rows})},
                  "labelled": {r["photo"]: r["category"] for r in rows if r["photo"] in labels}}
        write_json_and_markdown(out, {"config": config, "rows": rows, "summary": summary},
                                markdown(rows, summary, config))
        write_atomic(out / "sheet.png", sheet_png(entries), overwrite=True)
    return [{c: r[c] for c in COLUMNS} | {"top3": ", ".join(r["top3"])} for r in rows] + [summary_row(summary)]
