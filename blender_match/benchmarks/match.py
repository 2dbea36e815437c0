"""``blender-match bench match``: the paper's optimiser against ours on the same synthetic targets,
in one run, and the time each needs to reach the same loss.

Targets follow the paper's recovery protocol: a library graph rendered at 512 px with sampled
parameters (``sample_params(graph, 1)``) and graph seed 7; both optimisers start from the graph's
default parameters with seed 0, so no pixel alignment is possible. The paper's optimiser is Adam
at learning rate 5e-4 with the full 512/256/128 descriptor every iteration (``PAPER_SCHEDULE``,
cut to ``paper_iterations``). Ours is a quality preset. Every point our fit passed through is
re-scored afterwards with the paper's loss (not timed), so "seconds to the paper's loss" is the
time our fit needed to reach the paper optimiser's final loss by the paper's own measure.
"""
from __future__ import annotations

import tempfile
from pathlib import Path

import torch

from ..diffmat.descriptor import TextureDescriptor
from ..diffmat.optim import PAPER_SCHEDULE, QUALITY_SCHEDULES, TargetLoss, fit
from ..diffmat.render import render_maps
from ..library import apply_params, load_library_graph, sample_params
from ..pipeline import MatchOptions, match_photo

DEFAULT_GRAPHS = ("plaster", "marble")


def _target(name: str):
    graph = load_library_graph(name)
    apply_params(graph, sample_params(name, 1))
    with torch.no_grad():
        return render_maps(graph(size=512, seed=7))


def _paper_loss_of(graph, loss, theta_list):
    stage = PAPER_SCHEDULE.stages[0]
    with torch.no_grad():
        return [float(loss(graph, t[None], stage.size, stage.scales)[0]) for t in theta_list]


def time_to_reach(graph, loss, result, threshold: float, stride: int = 5) -> float | None:
    """Seconds at which ``result``'s fit first passed through a point whose paper loss is at most
    ``threshold`` (checked every ``stride`` snapshots, then the step before the first hit)."""
    snaps = result.snapshots
    indices = list(range(stride - 1, len(snaps), stride))
    if not indices or indices[-1] != len(snaps) - 1:
        indices.append(len(snaps) - 1)
    previous = -1
    for i in indices:
        if _paper_loss_of(graph, loss, [snaps[i][1]])[0] <= threshold:
            for j in range(previous + 1, i):  # the first hit inside the stride
                if _paper_loss_of(graph, loss, [snaps[j][1]])[0] <= threshold:
                    return snaps[j][0]
            return snaps[i][0]
        previous = i
    return None


def run(device: str = "cpu", graphs=DEFAULT_GRAPHS, paper_iterations: int = 30,
        quality: str = "balanced") -> list[dict]:
    descriptor = TextureDescriptor().to(device)
    rows = []
    for name in graphs:
        loss = TargetLoss(_target(name).to(device), descriptor)
        graph = load_library_graph(name).to(device)
        paper = fit(graph, loss, PAPER_SCHEDULE.scaled(paper_iterations))
        graph = load_library_graph(name).to(device)
        ours = fit(graph, loss, QUALITY_SCHEDULES[quality], keep_snapshots=True)
        ours_paper_loss = _paper_loss_of(graph, loss, [ours.theta])[0]
        reach = time_to_reach(graph, loss, ours, paper.loss_final)
        rows.append({
            "graph": name, "params": graph.num_params(),
            "loss_start": round(paper.loss_initial, 5),
            "paper_its": paper.iterations, "paper_s": round(paper.seconds, 1),
            "paper_loss": round(paper.loss_final, 5),
            f"{quality}_its": ours.iterations, f"{quality}_s": round(ours.seconds, 1),
            f"{quality}_loss": round(ours_paper_loss, 5),
            "reach_paper_s": None if reach is None else round(reach, 1),
            "speedup": None if reach is None else round(paper.seconds / max(reach, 1e-9), 1),
        })
    return rows


def run_pipeline(device: str = "auto", photo: str | None = None, graph: str = "plaster", quality: str = "balanced",
                 size: int = 2048) -> dict:
    """One ``match_photo`` run on a real photo: total seconds and per-stage seconds."""

    shared = Path(__file__).resolve().parents[2].parent / "shared" / "data" / "photos"
    photo = photo or str(shared / "real_plaster_wall_beige_desch18.png")
    with tempfile.TemporaryDirectory() as tmp:
        report = match_photo(photo, Path(tmp), MatchOptions(graph=graph, quality=quality, size=size, device=device))
    return {"graph": graph, "quality": quality, "size": size, "iterations": report["iterations"],
            "loss_initial": report["loss_initial"], "loss_final": report["loss_final"],
            "seconds": report["seconds"], **{f"{k}_s": v for k, v in report["stages"].items()}}

