"""Automatic graph selection and initialisation (the MATch paper, section 4.2).

``rank_graphs(photo)``: for every library graph with a current model, a candidate parameter
vector (the predictor's, the bank's nearest sample's, or both, keeping the better) is rendered at
128 px and scored by the fit's own style loss (Gram descriptor at 128) against the photo; the
graphs come best first, by that distance alone. Simplicity decides only the final choice among
the fitted graphs (below): ordering near-ties by simplicity here pushed the true graph out of the
top 3 on 2 of the 32 targets of ``bench selection`` (30/32 in the top 3 by distance, 28/32 with
the tie rule), while fitting one more candidate costs time, never the simpler answer (the
final choice still prefers it).

``select_and_fit(photo, k)``: the paper fits its top 3 graphs fully and keeps the best. We fit the
top ``k`` from their predicted start under one shared budget, by successive halving: every
candidate first gets a probe of ``PROBE_SHARE`` of the quality preset's iterations (at the
preset's first, cheapest stage); candidates whose probe loss is more than ``DROP_MARGIN`` worse
than the best are dropped, as is the worse half; the survivors share what is left of
``budget_factor(k)`` x the preset's iterations and run the preset's schedule (scaled) from their
probe's result. The best final loss wins; within ``TIE_TOLERANCE`` (2%) of it the simpler graph
(fewer nodes, then fewer parameters) does: it fits faster and edits more easily for the same look.

``choose_start(graph, name, loss, ...)``: a named library graph starts from the best of its
default, predicted and bank parameters by the loss at the first stage ("default" when no model).

``match_auto(...)`` is ``pipeline.match_photo``'s branch for ``options.graph is None``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import torch

from .bank import bank_is_current, current_bank, nearest
from .descriptor import DESCRIPTOR_SIZE, compact_descriptor, shared_vgg
from .predictor import load_predictor, predictor_is_current

METHODS = ("predictor", "bank", "both")
RANK_SIZE = 128
TIE_TOLERANCE = 0.02
PROBE_SHARE = 0.15
DROP_MARGIN = 0.10
NO_MODELS = ("automatic graph selection needs the selection models (parameter predictors or sample banks) "
             "and none were found in {where}; create them with `blender-match train --all`")


def budget_factor(k: int) -> float:
    """The shared budget of k candidates, in single-fit iteration budgets (1.5 for k = 3)."""
    return 1.0 + 0.25 * max(0, k - 1)


def available_models(method: str = "both", directory=None) -> list[str]:
    """Library graphs that have a current model of the kind ``method`` uses."""
    from ..library import library_names

    if method not in METHODS:
        raise ValueError(f"method {method!r}: expected one of {', '.join(METHODS)}")
    names = []
    for name in library_names():
        has_pred = method in ("predictor", "both") and predictor_is_current(name, directory)
        has_bank = method in ("bank", "both") and bank_is_current(name, directory)
        if has_pred or has_bank:
            names.append(name)
    return names


def simplicity(entry: dict) -> tuple:
    return (entry["nodes"], entry["params"])


def order_by_simplicity(entries: list[dict], tolerance: float = TIE_TOLERANCE, key: str = "distance") -> list[dict]:
    """Entries best (lowest ``key``) first, where everything within ``tolerance`` (relative) of
    the best remaining entry ties and the simplest of a tie (fewer nodes, then parameters) comes
    first."""
    left = sorted(entries, key=lambda e: e[key])
    out = []
    while left:
        best = left[0][key]
        limit = best + abs(best) * tolerance
        tied = [e for e in left if e[key] <= limit]
        pick = min(tied, key=lambda e: (*simplicity(e), e[key]))
        out.append(pick)
        left.remove(pick)
    return out


def _candidates(name, graph, descriptor, method, directory) -> list[tuple[str, torch.Tensor]]:
    """(start kind, normalised (P,) theta) the models propose for one graph."""
    out = []
    P = graph.num_params()
    if method in ("predictor", "both") and predictor_is_current(name, directory):
        model = load_predictor(name, directory)
        if model is not None and model.default.numel() == P:
            with torch.no_grad():
                out.append(("predicted", model(descriptor.cpu())[0].clamp(0, 1)))
    if method in ("bank", "both"):
        bank = current_bank(name, directory)
        if bank is not None and bank["thetas"].shape[1] == P:
            out.append(("bank", nearest(bank, descriptor.cpu())[0]["theta"]))
    return out


def _photo(photo) -> torch.Tensor:
    if photo.dim() == 3:
        photo = photo[None]
    if photo.dim() != 4 or photo.shape[:2] != (1, 3):
        raise ValueError(f"photo must be a (1, 3, H, W) RGB tensor, got {tuple(photo.shape)}")
    return photo.float().clamp(0, 1)


def _rank(photo, method, seed, device, directory, graphs, progress, cancel, gram=None, materials=None):
    """Ranking entries, each with its loaded graph under "material" (``materials``: a cache of
    loaded graphs by name, filled as graphs are loaded; they are only evaluated with explicit
    parameters here)."""
    from ..diffmat.descriptor import TextureDescriptor, style_loss
    from ..diffmat.optim import resize_square
    from ..diffmat.render import render_maps
    from ..library import library_entry, load_library_graph

    photo = _photo(photo).to(device)
    names = available_models(method, directory)
    if graphs is not None:
        names = [n for n in names if n in set(graphs)]
    if not names:
        from .bank import models_dir

        raise ValueError(NO_MODELS.format(where=models_dir(directory)))
    vgg = shared_vgg(device)
    if gram is None:
        gram = TextureDescriptor(scales=(RANK_SIZE,), vgg=vgg)
    with torch.no_grad():
        descriptor = compact_descriptor(vgg, photo, DESCRIPTOR_SIZE)
        target = gram(resize_square(photo, RANK_SIZE), (RANK_SIZE,))
    entries = []
    for index, name in enumerate(names):
        if cancel is not None and cancel():
            raise SelectionCancelled()
        if progress is not None:
            progress({"graph": name, "graph_index": index + 1, "graph_count": len(names)})
        graph = materials.get(name) if materials is not None else None
        if graph is None:
            graph = load_library_graph(name).to(device)
            graph.source = name
            if materials is not None:
                materials[name] = graph
        proposals = _candidates(name, graph, descriptor, method, directory)
        if not proposals:
            continue
        thetas = torch.stack([t for _, t in proposals]).to(device)
        with torch.no_grad():
            image = render_maps(graph(size=RANK_SIZE, seed=seed, theta=thetas)).clamp(0, 1)
            if image.shape[0] != thetas.shape[0]:
                image = image.expand(thetas.shape[0], -1, -1, -1)
            losses = style_loss(gram(image, (RANK_SIZE,)), target).cpu()
        losses = torch.where(torch.isfinite(losses), losses, torch.full_like(losses, math.inf))
        best = int(torch.argmin(losses))
        entry = library_entry(name)
        entries.append({"graph": name, "distance": float(losses[best]), "theta": proposals[best][1].cpu(),
                        "start": proposals[best][0], "nodes": entry["nodes"], "params": entry["params_optimizable"],
                        "material": graph})
        graph.clear_cache()
    return sorted(entries, key=lambda e: e["distance"])


class SelectionCancelled(Exception):
    """``cancel()`` returned True during selection or fitting."""


def rank_graphs(photo, method: str = "both", *, seed: int = 0, device="cpu", directory=None, graphs=None,
                progress=None, cancel=None, materials: dict | None = None) -> list[dict]:
    """Every library graph with a model, best first: {"graph", "distance" (style loss at 128 px of
    the proposed parameters' render), "theta" (normalised (P,)), "start" ("predicted" | "bank"),
    "nodes", "params"}. ``photo``: (1, 3, H, W) sRGB in [0, 1]; ``graphs`` limits the names;
    ``materials`` caches loaded graphs between calls."""
    entries = _rank(photo, method, seed, device, directory, graphs, progress, cancel, materials=materials)
    for e in entries:
        del e["material"]
    return entries


@dataclass
class Fitted:
    """One candidate's fit in ``select_and_fit``: ``material`` holds the fitted parameters."""

    graph: str
    material: object
    result: object
    start: str
    distance: float
    nodes: int
    params: int
    iterations: int = 0
    seconds: float = 0.0
    survived_probe: bool = True
    rounds: list = field(default_factory=list)

    def summary(self) -> dict:
        """For report.json. ``loss_final`` is the last round's, measured as that round's last stage
        measures: a graph dropped after the probe round was measured at the probe's size only, so
        its loss does not compare with the survivors'; ``rounds`` says which measure each used."""
        return {"graph": self.graph, "loss_final": round(self.result.loss_final, 6), "seconds": round(self.seconds, 3),
                "iterations": self.iterations, "start": self.start, "survived_probe": self.survived_probe,
                "rounds": self.rounds}


def _probe_schedule(schedule, iterations: int):
    from ..diffmat.optim import Schedule, Stage

    first = schedule.stages[0]
    return Schedule(f"{schedule.name}-probe", (Stage(first.size, first.scales, iterations, first.lr,
                                                     first.final_lr_ratio),), None, schedule.min_improvement)


def select_and_fit(photo, k: int = 3, quality: str = "balanced", seed: int = 0, progress=None, cancel=None, *,
                   method: str = "both", device="cpu", directory=None, iterations: int | None = None,
                   ranking: list[dict] | None = None, graphs=None, loss=None):
    """Fit the ``k`` best-ranked graphs under one shared budget (see the module docstring) and
    return ``(best, fitted)``: ``Fitted`` records, ``best.material`` with its fitted parameters
    set. ``ranking`` (from ``_rank``, with "material") skips ranking; ``iterations`` rescales the
    preset; ``progress`` gets {"graph", "graph_index", "graph_count", "iteration", "iterations",
    "loss", "eta_seconds"}; ``cancel()`` raises SelectionCancelled."""
    from ..diffmat.descriptor import TextureDescriptor
    from ..diffmat.optim import FitCancelled, TargetLoss, fit, quality_schedule

    if k < 1:
        raise ValueError(f"k must be at least 1, got {k}")
    photo = _photo(photo)
    schedule = quality_schedule(quality, iterations)
    if ranking is None:
        ranking = _rank(photo, method, seed, device, directory, graphs, None, cancel)
    chosen = ranking[:k]
    if loss is None:
        loss = TargetLoss(photo.to(device), TextureDescriptor(vgg=shared_vgg(device)))
    total = max(len(chosen), round(schedule.iterations * budget_factor(len(chosen))))
    probe = max(1, round(schedule.iterations * PROBE_SHARE)) if len(chosen) > 1 else 0
    state = {"done": 0}
    fits = [Fitted(e["graph"], e["material"], None, e["start"], e["distance"], e["nodes"], e["params"])
            for e in chosen]

    def run(f: Fitted, index: int, sched, theta0):
        def on_step(event):
            state["done"] += 1
            if progress is not None:
                progress({"graph": f.graph, "graph_index": index + 1, "graph_count": len(fits),
                          "iteration": state["done"], "iterations": total, "loss": event["loss"],
                          "eta_seconds": event["eta_seconds"]})
        try:
            result = fit(f.material, loss, sched, seed=seed, theta0=theta0, progress=on_step, cancel=cancel)
        except FitCancelled:
            raise SelectionCancelled() from None
        f.result = result
        f.iterations += result.iterations
        f.seconds += result.seconds
        last = sched.stages[-1]
        f.rounds.append({"schedule": sched.name, "iterations": result.iterations,
                         "loss_final": round(result.loss_final, 6),
                         "measured_at": {"size": last.size, "scales": list(last.scales)}})
        return result

    survivors = list(range(len(fits)))
    if probe:
        sched = _probe_schedule(schedule, probe)
        for i, f in enumerate(fits):
            run(f, i, sched, ranking[i]["theta"])
        best = min(f.result.loss_final for f in fits)
        ordered = sorted(survivors, key=lambda i: fits[i].result.loss_final)
        keep = max(1, math.ceil(len(fits) / 2))
        survivors = [i for i in ordered[:keep] if fits[i].result.loss_final <= best * (1 + DROP_MARGIN)]
        for i, f in enumerate(fits):
            f.survived_probe = i in survivors
    left = total - state["done"]
    share = max(1, left // len(survivors))
    main = schedule.scaled(share) if share != schedule.iterations else schedule
    for i in survivors:
        f = fits[i]
        start = f.result.theta if f.result is not None else ranking[i]["theta"]
        run(f, i, main, start)
    finals = [{"index": i, "loss": fits[i].result.loss_final, "nodes": fits[i].nodes, "params": fits[i].params}
              for i in survivors]
    winner = fits[order_by_simplicity(finals, key="loss")[0]["index"]]
    winner.material.set_vector(winner.result.theta)
    winner.material.clear_cache()
    return winner, fits


def choose_start(graph, name: str | None, loss, schedule, seed: int = 0, directory=None):
    """The start of a named graph's fit: (theta0 or None, "default" | "predicted" | "bank"), the
    best by the loss at the schedule's first stage of the default and what the models propose
    (models of a library graph, when current). The graph is left unchanged."""
    from ..library import library_names

    if name is None or name not in library_names():
        return None, "default"
    device = next(loss.descriptor.parameters()).device
    with torch.no_grad():
        descriptor = compact_descriptor(shared_vgg(device), loss.photo.to(device), DESCRIPTOR_SIZE)
    proposals = _candidates(name, graph, descriptor, "both", directory)
    if not proposals:
        return None, "default"
    proposals.insert(0, ("default", graph.get_vector()))
    first = schedule.stages[0]
    thetas = torch.stack([t for _, t in proposals]).to(device)
    with torch.no_grad():
        losses = loss(graph, thetas, first.size, first.scales, seed).cpu()
    losses = torch.where(torch.isfinite(losses), losses, torch.full_like(losses, math.inf))
    best = int(torch.argmin(losses))
    if best == 0:
        return None, "default"
    return proposals[best][1], proposals[best][0]


def match_auto(target, photo, out_dir, options, job, device) -> dict:
    """``match_photo`` without a graph: rank, fit the top 3 under one budget, write the best.
    ``target`` is the loaded photo, ``job`` the pipeline's progress tracker."""
    from ..diffmat.descriptor import TextureDescriptor
    from ..diffmat.optim import TargetLoss, quality_schedule
    from ..pipeline import MatchCancelled, _check_targets, _fit_report, _write_result

    class _NoMaps:  # before a graph is chosen, only the files every match writes can be checked
        outputs: dict = {}

    _check_targets(out_dir, _NoMaps, options.overwrite)
    torch.manual_seed(options.seed)
    job.stage("selecting")
    descriptor = TextureDescriptor(vgg=shared_vgg(device))
    gram = TextureDescriptor(scales=(RANK_SIZE,), vgg=descriptor.vgg)

    def on_rank(event):
        job.within((event["graph_index"] - 1) / event["graph_count"], **event)

    k = 3
    try:
        ranking = _rank(target, "both", options.seed, device, None, None, on_rank, job.cancel, gram=gram)
        job.stage("fitting", graph=ranking[0]["graph"], graph_index=1, graph_count=min(k, len(ranking)))

        def on_fit(event):
            job.within(event["iteration"] / event["iterations"], event["eta_seconds"], graph=event["graph"],
                       graph_index=event["graph_index"], graph_count=event["graph_count"],
                       iteration=event["iteration"], iterations=event["iterations"], loss=round(event["loss"], 6))

        loss = TargetLoss(target.to(device), descriptor)
        best, fits = select_and_fit(target, k, options.quality, options.seed, on_fit, job.cancel, device=device,
                                    iterations=options.iterations, ranking=ranking, loss=loss)
    except SelectionCancelled:
        raise MatchCancelled() from None
    graph = best.material
    schedule = quality_schedule(options.quality, options.iterations)
    extra = _fit_report(graph, best.result, schedule, photo, options.quality, best.start)
    _check_targets(out_dir, graph, options.overwrite)
    job.stage("writing maps")
    extra["iterations"] = sum(f.iterations for f in fits)  # every candidate's, not only the kept one's
    extra["fit"]["budget_iterations"] = round(schedule.iterations * budget_factor(len(fits)))
    extra["ranking"] = [{"graph": e["graph"], "distance": round(e["distance"], 6), "start": e["start"]}
                        for e in ranking]
    extra["fitted"] = [f.summary() for f in fits]
    return _write_result(graph, out_dir, options.size, options.seed, device, options.overwrite, job, photo=target,
                         report_extra=extra)
