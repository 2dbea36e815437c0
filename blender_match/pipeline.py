"""The matching pipeline that the CLI (``blender-match match``), the worker process and the Blender
add-on share: photo in, fitted procedural material out, as files in one folder.

``match_photo(photo, out_dir, options, progress, cancel)`` reads the photo, fits the graph
(``options.graph``), evaluates the fitted graph at ``options.size`` and writes, atomically:

    basecolor.png (sRGB, 8-bit)   normal.png (OpenGL, 16-bit)   roughness.png   metallic.png
    height.png (16-bit)           ambientocclusion.png (when the graph has it)
    params.json (reloadable: ``render_params``)   comparison.png (photo | render | maps)
    report.json (returned as a dict too)

``render_params(params_file, out_dir, size)`` re-renders a fitted material at another size
without the photo (the add-on's "re-render at 4K").

``progress(event)`` receives dicts: ``stage`` (one of ``STAGES``), ``fraction`` of the whole job
in [0, 1], ``eta_seconds`` (or None), and while fitting ``graph``, ``graph_index``,
``graph_count``, ``iteration``, ``iterations``, ``loss``. ``cancel()`` is polled at least once per
iteration; when it returns True the job stops with ``MatchCancelled`` and writes nothing.
"""
from __future__ import annotations

import json
import time
from dataclasses import dataclass
from pathlib import Path

QUALITIES = ("draft", "balanced", "best")
DEVICES = ("auto", "cpu", "cuda", "mps")
STAGES = ("reading photo", "selecting", "fitting", "writing maps")


class MatchCancelled(Exception):
    """The caller's cancel flag stopped the job; nothing was written."""


@dataclass
class MatchOptions:
    """What to match and how. ``graph``: a library graph's name, a bundled graph's name or a
    ``.sbs`` path (None: automatic selection). ``iterations`` overrides the quality preset's
    iteration count (tests and scripted drafts)."""

    graph: str | None = None
    size: int = 2048
    quality: str = "balanced"
    seed: int = 0
    device: str = "auto"
    overwrite: bool = False
    iterations: int | None = None


MATCH_FILES = ("params.json", "comparison.png", "report.json")
COMPARISON_TILE = 256
PHOTO_SIZE = 512  # the photo is described at 512 at most (the paper's largest scale)
# share of the whole job each stage takes, for the progress fraction: with a named graph, and with
# automatic selection (ranking the library's 16 graphs takes about 5% of a balanced auto match)
_STAGE_SHARE = {"reading photo": 0.02, "fitting": 0.88, "writing maps": 0.10}
_AUTO_STAGE_SHARE = {"reading photo": 0.02, "selecting": 0.05, "fitting": 0.83, "writing maps": 0.10}


class MatchFailed(ValueError):
    """The fit produced no usable material (a non-finite loss or map); nothing was written."""


def load_graph(source: str):
    """A MaterialGraph from a bundled graph's name, a library graph's name or an .sbs path."""
    from .bundled_graphs import BUNDLED, build
    from .library import library_names, load_library_graph

    if source in BUNDLED:
        return build(source)
    if source in library_names():
        return load_library_graph(source)
    path = Path(source)
    if path.suffix.lower() == ".sbs":
        from .translator import load_sbs_graph

        return load_sbs_graph(path)
    raise ValueError(f"{source}: not a bundled graph ({', '.join(sorted(BUNDLED))}), a library graph "
                     f"({', '.join(library_names()) or 'none built'}) nor a .sbs file")


def resolve_device(name: str):
    """The torch device for "auto", "cpu", "cuda" or "mps" (a clear error when it is absent)."""
    import torch

    if name not in DEVICES:
        raise ValueError(f"device {name!r}: expected one of {', '.join(DEVICES)}")
    if name == "auto":
        if torch.cuda.is_available():
            return torch.device("cuda")
        if getattr(torch.backends, "mps", None) is not None and torch.backends.mps.is_available():
            return torch.device("mps")
        return torch.device("cpu")
    if name == "cuda" and not torch.cuda.is_available():
        raise ValueError("device cuda: no CUDA GPU is available to this torch")
    if name == "mps" and not (getattr(torch.backends, "mps", None) and torch.backends.mps.is_available()):
        raise ValueError("device mps: Metal is not available to this torch")
    return torch.device(name)


def _check_size(size) -> int:
    if isinstance(size, bool) or not isinstance(size, int) or size < 16 or size > 8192 or size & (size - 1):
        raise ValueError(f"size {size!r}: expected a power of two between 16 and 8192")
    return size


def _check_targets(out_dir, graph, overwrite: bool, extra=MATCH_FILES):
    """Refuse, before any work, to replace existing files of a result folder."""

    from .material_maps import MAP_FILES

    if overwrite:
        return
    names = [MAP_FILES[u][0] for u in graph.outputs if u in MAP_FILES] + list(extra)
    existing = [Path(out_dir) / n for n in names if (Path(out_dir) / n).exists()]
    if existing:
        raise FileExistsError(f"{existing[0]}: already exists (use --overwrite to replace it)")


class _Progress:
    """Turns stage-local progress into job-wide events (fraction of the whole, time left)."""

    def __init__(self, callback, cancel, shares: dict[str, float] = _STAGE_SHARE):
        self.callback, self.cancel, self.shares = callback, cancel, shares
        self.start = time.perf_counter()
        self.stage_seconds: dict[str, float] = {}
        self._stage, self._stage_start, self._done = None, self.start, 0.0

    def stage(self, name: str, **extra):
        now = time.perf_counter()
        if self._stage is not None:
            self.stage_seconds[self._stage] = round(now - self._stage_start, 3)
            self._done += self.shares[self._stage]
        self._stage, self._stage_start = name, now
        if name is not None:
            self.check_cancel()
            self.emit({"stage": name, "fraction": round(self._done, 4), "eta_seconds": None, **extra})

    def within(self, local_fraction: float, eta_seconds=None, **extra):
        share = self.shares[self._stage]
        self.emit({"stage": self._stage, "fraction": round(self._done + share * min(1.0, local_fraction), 4),
                   "eta_seconds": None if eta_seconds is None else round(eta_seconds, 1), **extra})

    def emit(self, event: dict):
        if self.callback is not None:
            self.callback(event)

    def check_cancel(self):
        if self.cancel is not None and self.cancel():
            raise MatchCancelled()


def _write_result(graph, out_dir, size: int, seed: int, device, overwrite: bool, progress: _Progress,
                  photo=None, report_extra: dict | None = None) -> dict:
    """Evaluate the graph at ``size`` and write maps, params.json, comparison.png, report.json."""
    import torch

    from .diffmat.params_file import graph_params
    from .image_files import write_png
    from .material_maps import write_maps
    from .safe_files import write_atomic

    out_dir = Path(out_dir)
    with torch.no_grad():
        maps = graph(size=size, seed=seed)
        bad = [u for u, m in maps.items() if not torch.isfinite(m).all()]
        if bad:
            raise MatchFailed(f"graph {graph.name}: the fitted {bad[0]} map is not finite; nothing written")
        progress.check_cancel()
        comparison = _comparison_image(maps, photo)
    maps = {u: m.cpu() for u, m in maps.items()}
    progress.within(0.3)
    written = write_maps(maps, out_dir, overwrite=overwrite)
    params = {"graph": graph.name, "source": graph.source, "seed": seed, "params": graph_params(graph)}
    write_atomic(out_dir / "params.json", json.dumps(params, indent=1).encode("utf-8"), overwrite=overwrite)
    write_png(out_dir / "comparison.png", comparison, overwrite=overwrite)
    progress.stage(None)
    report = {"graph": graph.name, "source": graph.source, "size": size, "seed": seed, "device": str(device),
              **(report_extra or {}), "maps": written, "params_file": "params.json",
              "comparison": "comparison.png", "stages": progress.stage_seconds}
    report["seconds"] = round(time.perf_counter() - progress.start, 3)
    write_atomic(out_dir / "report.json", json.dumps(report, indent=1).encode("utf-8"), overwrite=overwrite)
    return report


def _comparison_image(maps: dict, photo):
    """One row of COMPARISON_TILE squares: the photo (when given), the render, then every map."""
    import torch

    from .diffmat.optim import resize_square
    from .diffmat.render import render_maps
    from .material_maps import to_channels

    tiles = [] if photo is None else [photo]
    tiles.append(render_maps(maps)[:1] if "basecolor" in maps else None)
    tiles.extend(to_channels(maps[u][:1], 3) for u in ("basecolor", "normal", "roughness", "metallic", "height")
                 if u in maps)
    tiles = [resize_square(t.float().cpu().clamp(0, 1), COMPARISON_TILE) for t in tiles if t is not None]
    return torch.cat(tiles, dim=3)


def match_photo(photo, out_dir, options: MatchOptions, progress=None, cancel=None) -> dict:
    """Fit ``options.graph`` to the photo and write the result folder (see the module docstring)."""
    import torch

    from .diffmat.optim import FitCancelled, quality_schedule
    from .photo import load_photo

    if options.quality not in QUALITIES:
        raise ValueError(f"quality {options.quality!r}: expected one of {', '.join(QUALITIES)}")
    size = _check_size(options.size)
    device = resolve_device(options.device)
    job = _Progress(progress, cancel, _STAGE_SHARE if options.graph else _AUTO_STAGE_SHARE)
    job.stage("reading photo")
    target = load_photo(Path(photo), PHOTO_SIZE)
    if options.graph is None:  # automatic selection: rank the library, fit the best 3, keep one
        from .selection.select import match_auto

        return match_auto(target, photo, out_dir, options, job, device)
    graph = load_graph(options.graph)
    graph.source = options.graph
    _check_targets(out_dir, graph, options.overwrite)
    torch.manual_seed(options.seed)
    job.stage("fitting", graph=graph.name, graph_index=1, graph_count=1)
    schedule = quality_schedule(options.quality, options.iterations)

    def on_step(event):
        job.within(event["iteration"] / schedule.iterations, event["eta_seconds"], graph=graph.name,
                   graph_index=1, graph_count=1, iteration=event["iteration"], iterations=schedule.iterations,
                   loss=round(event["loss"], 6))

    try:
        result, start, _ = fit_named_graph(graph, options.graph, target, schedule, options.seed, device,
                                        progress=on_step, cancel=job.cancel)
    except FitCancelled:
        raise MatchCancelled() from None
    fitted = _fit_report(graph, result, schedule, photo, options.quality, start)
    graph.set_vector(result.theta)
    graph.clear_cache()
    job.stage("writing maps")
    return _write_result(graph, out_dir, size, options.seed, device, options.overwrite, job, photo=target,
                         report_extra=fitted)


def fit_named_graph(graph, name: str, target, schedule, seed: int, device, progress=None, cancel=None):
    """Fit ``graph`` (the graph called ``name``) to the photo tensor ``target`` from the start the
    product chooses (default, bank or predicted parameters: ``choose_start``): (FitResult, the
    start's name, the start's parameter vector). The graph is moved to ``device``; its parameters
    are left unchanged."""
    from .diffmat.descriptor import TextureDescriptor
    from .diffmat.optim import TargetLoss, fit
    from .selection.descriptor import shared_vgg
    from .selection.select import choose_start

    graph.to(device)
    loss = TargetLoss(target.to(device), TextureDescriptor(vgg=shared_vgg(device)))  # choose_start shares it
    theta0, start = choose_start(graph, name, loss, schedule, seed)
    if theta0 is None:
        theta0 = graph.get_vector()
    result = fit(graph, loss, schedule, seed=seed, theta0=theta0, progress=progress, cancel=cancel)
    return result, start, theta0.detach().cpu()


def _fit_report(graph, result, schedule, photo, quality: str, start: str) -> dict:
    """The fit's part of report.json (a named graph's or the kept one of automatic selection);
    raises MatchFailed when the fit diverged, before anything is written."""
    import torch

    if not torch.isfinite(result.theta).all():
        raise MatchFailed(f"graph {graph.name}: the fit diverged (non-finite parameters); nothing written")
    return {"photo": str(photo), "quality": quality, "loss_initial": round(result.loss_initial, 6),
            "loss_final": round(result.loss_final, 6), "iterations": result.iterations, "start": start,
            "fit": {"schedule": schedule.name, "stopped": result.stopped,
                    "stage_seconds": [round(s, 3) for s in result.stage_seconds],
                    "parameters": graph.num_params()}}


def render_params(params_file, out_dir, size: int, device: str = "auto", overwrite: bool = False,
                  progress=None, cancel=None) -> dict:
    """Re-render a fitted material (its params.json) at ``size`` into ``out_dir``, no photo needed."""

    from .diffmat.params_file import load_params, read_params_file

    params_file = Path(params_file)
    data = read_params_file(params_file)
    if not isinstance(data.get("source"), str):
        raise ValueError(f"{params_file}: no \"source\" graph recorded (was it written by a match?)")
    size = _check_size(size)
    torch_device = resolve_device(device)
    job = _Progress(progress, cancel)
    graph = load_graph(data["source"])
    graph.source = data["source"]
    load_params(graph, params_file)
    _check_targets(out_dir, graph, overwrite)
    graph.to(torch_device)
    job.stage("writing maps")
    return _write_result(graph, out_dir, size, int(data.get("seed", 0)), torch_device, overwrite, job,
                         report_extra={"rendered_from": str(params_file)})
