"""Result folders: what a match or a re-render writes, and the refusal, before any work, to
replace files that are already there.

A result folder holds the material's maps (``vocabulary.MATERIAL_OUTPUTS``: basecolor.png sRGB
8-bit, normal.png OpenGL 16-bit, roughness.png, metallic.png, height.png 16-bit,
ambientocclusion.png, anisotropylevel.png and anisotropyangle.png when the graph has them),
``params.json`` (reloadable: ``pipeline.render_params``), ``comparison.png`` (photo | render |
maps) and ``report.json``.
"""
from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

import torch

from ..diffmat import MaterialGraph
from ..diffmat.calibration import framed_maps
from ..diffmat.optim import resize_square
from ..diffmat.params_file import save_params
from ..diffmat.render import FlashCamera, render_maps
from ..errors import BlenderMatchError
from ..image_files import write_png
from ..material_maps import to_channels, write_maps
from ..safe_files import FileWriteError, write_json_atomic
from ..vocabulary import ANISOTROPY, AUTHORED_USAGES, COMPARISON_FILE, OUTPUTS, PARAMS_FILE, REPORT_FILE
from .progress import JobProgress

MATCH_FILES = (PARAMS_FILE, COMPARISON_FILE, REPORT_FILE)
COMPARISON_TILE = 256
COMPARED_MAPS = (*AUTHORED_USAGES, ANISOTROPY)  # the maps comparison.png shows, when the graph has them


class MatchFailed(BlenderMatchError):
    """The fit produced no usable material (a non-finite loss or map); nothing was written."""


def refuse_existing(paths: Iterable[Path], overwrite: bool) -> None:
    """FileWriteError naming the first of ``paths`` that exists, unless ``overwrite``."""
    if overwrite:
        return
    existing = [Path(p) for p in paths if Path(p).exists()]
    if existing:
        raise FileWriteError(f"{existing[0]}: already exists (use --overwrite to replace it)")


def check_targets(out_dir, usages: Iterable[str], overwrite: bool, extra: Iterable[str] = MATCH_FILES) -> None:
    """Refuse, before any work, to replace the files of ``usages``' maps and ``extra`` in ``out_dir``."""
    names = [OUTPUTS[u].file for u in usages if u in OUTPUTS] + list(extra)
    refuse_existing((Path(out_dir) / n for n in names), overwrite)


def evaluate_maps(graph: MaterialGraph, size: int, seed: int) -> dict[str, torch.Tensor]:
    """The graph's maps at ``size`` (no gradients); MatchFailed when one is not finite."""
    with torch.no_grad():
        maps = graph(size=size, seed=seed)
    bad = [u for u, m in maps.items() if not torch.isfinite(m).all()]
    if bad:
        raise MatchFailed(f"graph {graph.name}: the fitted {bad[0]} map is not finite; nothing written")
    return maps


def comparison_image(graph: MaterialGraph, maps: dict[str, torch.Tensor], photo: torch.Tensor | None,
                     seed: int, camera: FlashCamera = FlashCamera()) -> torch.Tensor:
    """One row of COMPARISON_TILE squares: the photo (when given), the render, then every authored
    map and the anisotropy level (``COMPARED_MAPS``; the angle, one grey on every graph of ours, is
    left to its file).
    Beside a photo the render is the graph as the fit saw it: at the photo's size and zoom
    (``calibration.framed_maps``), under ``camera`` (the photo's flash); alone, it is one period
    of ``maps`` (under the ideal flash, the only one a caller without a photo has)."""
    with torch.no_grad():
        tiles: list[torch.Tensor | None] = [] if photo is None else [photo]
        shown = maps if photo is None else framed_maps(graph, photo.shape[-1], seed)
        tiles.append(render_maps(shown, camera)[:1] if "basecolor" in maps else None)
        tiles.extend(to_channels(maps[u][:1], 3) for u in COMPARED_MAPS if u in maps)
        squares = [resize_square(t.float().cpu().clamp(0, 1), COMPARISON_TILE) for t in tiles if t is not None]
        return torch.cat(squares, dim=3)


def write_result(graph: MaterialGraph, source: str, out_dir, size: int, seed: int, device, overwrite: bool,
                 progress: JobProgress, photo: torch.Tensor | None = None, camera: FlashCamera = FlashCamera(),
                 report_extra: dict | None = None) -> dict:
    """Evaluate the graph at ``size`` and write maps, params.json, comparison.png and report.json;
    returns the report. ``source`` names the graph as ``pipeline.load_graph`` loads it again."""
    out_dir = Path(out_dir)
    maps = evaluate_maps(graph, size, seed)
    progress.check_cancel()
    comparison = comparison_image(graph, maps, photo, seed, camera)
    maps = {u: m.cpu() for u, m in maps.items()}
    progress.within(0.3)
    written = write_maps(maps, out_dir, overwrite=overwrite)
    save_params(graph, out_dir / PARAMS_FILE, overwrite, source=source, seed=seed)
    write_png(out_dir / COMPARISON_FILE, comparison, overwrite=overwrite)
    progress.stage(None)
    report = {"graph": graph.name, "source": source, "size": size, "seed": seed, "device": str(device),
              **(report_extra or {}), "maps": written, "params_file": PARAMS_FILE,
              "comparison": COMPARISON_FILE, "stages": progress.stage_seconds, "seconds": progress.seconds()}
    write_json_atomic(out_dir / REPORT_FILE, report, overwrite)
    return report
