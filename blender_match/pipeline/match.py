"""The matching flow: a photo in, a fitted material out, with a named graph or by automatic
selection, written as a result folder (``match_photo``) or returned (``fit_photo``).

With ``options.graph`` the graph is fitted from the start the product chooses (default, bank or
predicted parameters: ``selection.choose_start``). Without it the library is ranked for the
photo and the best ``options.candidates`` graphs (``AUTO_CANDIDATES``: the first) are fitted
under one shared budget, the best kept (``selection.select_and_fit``). The photo is read once
and moved to the device once; the quality preset becomes the optimiser's schedule once
(``match_schedule``).
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import torch

from ..diffmat import MaterialGraph
from ..diffmat.calibration import solve_gain, solve_lighting
from ..diffmat.descriptor import TextureDescriptor
from ..diffmat.optim import FitResult, Schedule, TargetLoss, fit
from ..diffmat.render import FlashCamera
from ..photo import load_photo
from ..selection import budget_factor, check_photo, choose_start, frame_start, rank_graphs, select_and_fit, shared_vgg
from ..vocabulary import FALLOFF, FITTING, GAIN, READING_PHOTO, SELECTING, WRITING_MAPS, ZOOM
from .device import resolve_device
from .graphs import load_graph
from .options import PHOTO_SIZE, MatchOptions, check_candidates, check_size, check_zoom, match_schedule
from .progress import AUTO_SHARES, NAMED_SHARES, JobProgress
from .result_folder import MATCH_FILES, MatchFailed, check_targets, write_result

Progress = Callable[[dict], None]
Cancel = Callable[[], bool]
OutputsCheck = Callable[[list[str], tuple[str, ...]], None]


@dataclass
class Match:
    """A fitted material: ``graph`` with its fitted parameters set (on ``device``), ``source`` the
    name ``load_graph`` loads it by, ``photo`` the (1, 3, S, S) sRGB photo it was fitted to (on
    ``device``), ``report`` the fit's part of report.json, ``camera`` the photo's flash as the fit
    found it (its falloff: a property of the photo, not of the material, so no map carries it)."""

    graph: MaterialGraph
    source: str
    photo: torch.Tensor
    device: torch.device
    report: dict = field(default_factory=dict)
    camera: FlashCamera = FlashCamera()


def fit_report(graph: MaterialGraph, result: FitResult, schedule: Schedule, photo, quality: str,
               start: str) -> dict:
    """The fit's part of report.json (a named graph's or the kept one of automatic selection);
    raises MatchFailed when the fit diverged, before anything is written."""
    if not torch.isfinite(result.theta).all():
        raise MatchFailed(f"graph {graph.name}: the fit diverged (non-finite parameters); nothing written")
    return {"photo": str(photo), "quality": quality, "loss_initial": round(result.loss_initial, 6),
            "loss_final": round(result.loss_final, 6), "iterations": result.iterations, "start": start,
            "fit": {"schedule": schedule.name, "stopped": result.stopped,
                    "stage_seconds": [round(s, 3) for s in result.stage_seconds],
                    "parameters": graph.num_params()}}


def photo_loss(target: torch.Tensor, device) -> TargetLoss:
    """The fit's loss against ``target`` (moved to ``device``), with the process's shared VGG."""
    return TargetLoss(target.to(device), TextureDescriptor(vgg=shared_vgg(device)))


def fit_named_graph(graph: MaterialGraph, name: str | None, target: torch.Tensor, schedule: Schedule, seed: int,
                    device, zoom: float | None = 1.0, lighting: bool = True, calibrate: bool = True,
                    progress=None, cancel=None) -> tuple[FitResult, str, torch.Tensor, FlashCamera]:
    """Fit ``graph`` (the graph called ``name``) to the photo tensor ``target`` from the start the
    product chooses (default, bank or predicted parameters: ``choose_start``), framed at ``zoom``
    (None: searched from that start), when ``lighting`` under the photo's flash falloff and when
    ``calibrate`` with the base colour gain, both solved at that start (``selection.frame_start``):
    (FitResult, the start's name, the start's parameter vector, the camera of the fit). The graph
    is moved to ``device``; its parameters are left unchanged, its zoom and gain are set."""
    graph.to(device)
    loss = photo_loss(target, device)  # choose_start shares it
    theta0, start = choose_start(graph, name, loss, schedule, seed)
    if theta0 is None:
        theta0 = graph.get_vector()
    loss.camera = frame_start(graph, loss, theta0, schedule, seed, zoom, lighting, calibrate)
    result = fit(graph, loss, schedule, seed=seed, theta0=theta0, progress=progress, cancel=cancel)
    return result, start, theta0.detach().cpu(), loss.camera


def finish_calibration(graph: MaterialGraph, target: torch.Tensor, seed: int, camera: FlashCamera,
                       lighting: bool = True, calibrate: bool = True) -> tuple[FlashCamera, dict]:
    """What every match does once the fitted parameters are set on ``graph``: the photo's flash
    falloff solved again for the fitted material (when ``lighting``), then the gain that gives its
    base colour the photo's exposure and white balance under that light (when ``calibrate``; the
    gain solved at the start no longer fits a material whose colour and relief the fit moved).
    Returns the camera and report.json's ``calibration`` entries (zoom, falloff, gain)."""
    entries: dict = {ZOOM: graph.calibration.periods()}
    if lighting:
        camera = solve_lighting(graph, target, seed, camera)
        entries[FALLOFF] = [round(v, 4) for v in camera.falloff]
    if calibrate and "basecolor" in graph.outputs:
        gain = solve_gain(graph, target, seed=seed, camera=camera)
        entries[GAIN] = [round(float(v), 4) for v in gain]
    return camera, entries


def _fitting_progress(job: JobProgress, event: dict) -> None:
    """One fitting step as a job-wide progress event: ``event`` holds the graph, its index and
    count, the iteration of all ``iterations``, the loss and the time left."""
    job.within(event["iteration"] / event["iterations"], event["eta_seconds"], graph=event["graph"],
               graph_index=event["graph_index"], graph_count=event["graph_count"],
               iteration=event["iteration"], iterations=event["iterations"], loss=round(event["loss"], 6))


def _fit_named(job: JobProgress, target: torch.Tensor, options: MatchOptions, schedule: Schedule, photo_name: str,
               check_outputs: OutputsCheck | None) -> tuple[MaterialGraph, str, dict, FlashCamera]:
    assert options.graph is not None
    graph = load_graph(options.graph)
    if check_outputs is not None:
        check_outputs(list(graph.outputs), MATCH_FILES)
    torch.manual_seed(options.seed)
    job.stage(FITTING, graph=graph.name, graph_index=1, graph_count=1)

    def on_step(event):
        _fitting_progress(job, {**event, "graph": graph.name, "graph_index": 1, "graph_count": 1,
                               "iterations": schedule.iterations})

    result, start, _, camera = fit_named_graph(graph, options.graph, target, schedule, options.seed, target.device,
                                               zoom=options.zoom, lighting=options.lighting,
                                               calibrate=options.calibrate, progress=on_step,
                                               cancel=job.cancel)
    report = fit_report(graph, result, schedule, photo_name, options.quality, start)
    graph.set_vector(result.theta)
    graph.clear_cache()
    return graph, options.graph, report, camera


def _fit_auto(job: JobProgress, target: torch.Tensor, options: MatchOptions, schedule: Schedule, photo_name: str,
              check_outputs: OutputsCheck | None) -> tuple[MaterialGraph, str, dict, FlashCamera]:
    if check_outputs is not None:  # before a graph is chosen, only the files every match writes
        check_outputs([], MATCH_FILES)
    torch.manual_seed(options.seed)
    job.stage(SELECTING)

    def on_rank(event):
        job.within((event["graph_index"] - 1) / event["graph_count"], **event)

    materials: dict[str, MaterialGraph] = {}
    ranking = rank_graphs(target, "both", seed=options.seed, device=target.device, progress=on_rank,
                          cancel=job.cancel, materials=materials)
    k = options.candidates
    job.stage(FITTING, graph=ranking[0]["graph"], graph_index=1, graph_count=min(k, len(ranking)))
    loss = photo_loss(target, target.device)
    best, fits = select_and_fit(loss, ranking, k, schedule, seed=options.seed, materials=materials,
                                zoom=options.zoom, lighting=options.lighting, calibrate=options.calibrate,
                                progress=lambda event: _fitting_progress(job, event), cancel=job.cancel)
    graph = best.material
    report = fit_report(graph, best.fitted, schedule, photo_name, options.quality, best.start)
    if check_outputs is not None:
        check_outputs(list(graph.outputs), MATCH_FILES)
    report["iterations"] = sum(f.iterations for f in fits)  # every candidate's, not only the kept one's
    report["fit"]["budget_iterations"] = round(schedule.iterations * budget_factor(len(fits)))
    report["ranking"] = [{"graph": e["graph"], "distance": round(e["distance"], 6), "start": e["start"],
                          "gain": e["gain"]} for e in ranking]
    report["fitted"] = [f.summary() for f in fits]
    return graph, best.graph, report, loss.camera


def _fit(job: JobProgress, photo, options: MatchOptions, schedule: Schedule, device: torch.device,
         check_outputs: OutputsCheck | None) -> Match:
    """Read the photo and fit (named or automatic; either frames the graph at the photo's scale
    and light), then ``finish_calibration`` (as ``options.lighting`` and ``options.calibrate``
    say): what ``fit_photo`` and ``match_photo`` share. The photo is moved to the device once, here."""
    job.stage(READING_PHOTO)
    if isinstance(photo, torch.Tensor):
        target, photo_name = check_photo(photo), "photo"
    else:
        target, photo_name = load_photo(Path(photo), PHOTO_SIZE), str(photo)
    target = target.to(device)
    branch = _fit_named if options.graph else _fit_auto
    graph, source, report, camera = branch(job, target, options, schedule, photo_name, check_outputs)
    camera, report["calibration"] = finish_calibration(graph, target, options.seed, camera, options.lighting,
                                                       options.calibrate)
    return Match(graph, source, target, device, report, camera)


def fit_photo(photo, options: MatchOptions, progress: Progress | None = None,
              cancel: Cancel | None = None) -> Match:
    """Fit a material to ``photo`` (a path, or a (1, 3, S, S) sRGB tensor as ``load_photo``
    returns) as ``match_photo`` does, without writing anything: the fitted ``Match``.
    ``options.size`` and ``options.overwrite`` play no part."""
    schedule = match_schedule(options.quality, options.iterations)
    check_candidates(options.candidates)
    check_zoom(options.zoom)
    device = resolve_device(options.device)
    job = JobProgress(progress, cancel, NAMED_SHARES if options.graph else AUTO_SHARES)
    match = _fit(job, photo, options, schedule, device, None)
    job.stage(None)
    match.report["stages"] = job.stage_seconds
    return match


def match_photo(photo, out_dir, options: MatchOptions, progress: Progress | None = None,
                cancel: Cancel | None = None) -> dict:
    """Fit a material to the photo and write the result folder ``out_dir``
    (``pipeline.result_folder``); returns report.json's content. Existing files are refused
    before any work unless ``options.overwrite``."""
    schedule = match_schedule(options.quality, options.iterations)
    check_candidates(options.candidates)
    check_zoom(options.zoom)
    size = check_size(options.size)
    device = resolve_device(options.device)
    job = JobProgress(progress, cancel, NAMED_SHARES if options.graph else AUTO_SHARES)

    def check_outputs(usages, extra):
        check_targets(out_dir, usages, options.overwrite, extra)

    match = _fit(job, photo, options, schedule, device, check_outputs)
    job.stage(WRITING_MAPS)
    return write_result(match.graph, match.source, out_dir, size, options.seed, device, options.overwrite, job,
                        photo=match.photo, camera=match.camera, report_extra=match.report)
