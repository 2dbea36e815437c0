"""Fitting the best-ranked graphs and keeping one (the MATch paper, section 4.2).

The paper fits its top 3 graphs fully and keeps the best. ``select_and_fit`` fits the top ``k``
of a ranking (``selection.rank``) from their proposed start under one shared budget, by
successive halving: every candidate first gets a probe of ``PROBE_SHARE`` of the schedule's
iterations (at the schedule's first, cheapest stage); candidates whose probe loss is more than
``DROP_MARGIN`` worse than the best are dropped, as is the worse half; the survivors share what
is left of ``budget_factor(k)`` x the schedule's iterations and run the schedule (scaled) from
their probe's result. The best final loss wins; within ``TIE_TOLERANCE`` (2%) of it the simpler
graph (fewer nodes, then fewer parameters) does: it fits faster and edits more easily for the same
look.

Losses are compared with a handicap for the place in the ranking: the candidate ranked ``i``-th
(from 0) counts its loss times ``(1 + RANK_MARGIN) ** i``, at the probe and at the end, so that
a graph ranked lower must fit clearly better to displace a better-ranked one. On real photos the
fit's own loss favours the graphs that can absorb a photo's lighting and colour, whatever their
material, where the ranking (every graph judged from one proposed start, at one size) more often
names the photo's family (docs/benchmarks.md).

Before its first round each candidate is framed at the photo's scale and light: its zoom is
searched from its start (``diffmat.zoom_search``) unless the caller fixes it, then the falloff of
the photo's flash over the frame is solved against the start's render
(``calibration.solve_lighting``), so that the fit need not bend the material to imitate a
phone's beam pattern and vignetting, and the gain on its base colour that gives the start's
render the photo's exposure and white balance (``calibration.solve_gain``), so that the fit need
not spend the graph's colour parameters on them (the ranking judged it with that gain). Each
candidate fits under its own camera and keeps its own gain.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import torch

from ..diffmat import MaterialGraph
from ..diffmat.calibration import solve_gain, solve_lighting
from ..diffmat.optim import FitResult, Schedule, TargetLoss, fit
from ..diffmat.render import FlashCamera
from ..diffmat.zoom_search import search_zoom
from ..errors import OptionError
from ..vocabulary import ZOOM
from .rank import load_material, order_by_simplicity

PROBE_SHARE = 0.15
DROP_MARGIN = 0.10
RANK_MARGIN = 0.25


def budget_factor(k: int) -> float:
    """The shared budget of k candidates, in single-fit iteration budgets (1.5 for k = 3)."""
    return 1.0 + 0.25 * max(0, k - 1)


@dataclass
class Fitted:
    """One candidate's fit in ``select_and_fit``: ``material`` holds the fitted parameters."""

    graph: str
    material: MaterialGraph
    start: str
    distance: float
    nodes: int
    params: int
    camera: FlashCamera = FlashCamera()
    result: FitResult | None = None
    iterations: int = 0
    seconds: float = 0.0
    survived_probe: bool = True
    rounds: list = field(default_factory=list)

    @property
    def fitted(self) -> FitResult:
        """The result of the candidate's last fit round (it has had one once ``select_and_fit`` returns)."""
        assert self.result is not None, f"{self.graph}: not fitted yet"
        return self.result

    def summary(self) -> dict:
        """For report.json. ``loss_final`` is the last round's, measured as that round's last stage
        measures: a graph dropped after the probe round was measured at the probe's size only, so
        its loss does not compare with the survivors'; ``rounds`` says which measure each used."""
        return {"graph": self.graph, "loss_final": round(self.fitted.loss_final, 6), "seconds": round(self.seconds, 3),
                "iterations": self.iterations, "start": self.start, "survived_probe": self.survived_probe,
                "zoom": self.material.calibration.periods(), "rounds": self.rounds}


def probe_schedule(schedule: Schedule, iterations: int) -> Schedule:
    """The schedule's first stage alone, for ``iterations``: the probe round."""
    first = schedule.stages[0]
    return Schedule(f"{schedule.name}-probe", (replace(first, iterations=iterations, warmup=0),), None,
                    schedule.min_improvement)


def frame_start(graph, loss: TargetLoss, theta: torch.Tensor, schedule: Schedule, seed: int = 0,
                zoom: float | None = 1.0, lighting: bool = True, calibrate: bool = True) -> FlashCamera:
    """Set ``graph``'s zoom (``zoom`` when given, else the one ``search_zoom`` finds for the start
    ``theta`` at ``schedule``'s first stage) and return the camera to fit it under: ``loss``'s,
    with the photo's falloff solved at the start when ``lighting``. The falloff is solved before
    the search too, at the graph's current zoom, so that each zoom is judged under the photo's
    light (under the ideal flash a coarse start zoomed out can look closer to a vignetted photo
    than the right scale does). When ``calibrate`` (and the graph has a base colour), its gain is
    then solved for the start under that camera. ``loss.camera`` and the graph's parameters are
    left as they were."""
    ideal = loss.camera
    if zoom is not None:
        graph.calibration.set_values(**{ZOOM: zoom})
    else:
        if lighting:
            loss.camera = solve_lighting(graph, loss.photo, seed, ideal, theta)
        first = schedule.stages[0]
        search_zoom(graph, loss, theta, first.size, first.scales, seed)
        loss.camera = ideal
    graph.clear_cache()
    camera = solve_lighting(graph, loss.photo, seed, ideal, theta) if lighting else ideal
    if calibrate and "basecolor" in graph.outputs:
        solve_gain(graph, loss.photo, seed, camera, theta=theta)
        graph.clear_cache()
    return camera


def select_and_fit(loss: TargetLoss, ranking: list[dict], k: int, schedule: Schedule, *, seed: int = 0,
                   materials: dict | None = None, zoom: float | None = 1.0, lighting: bool = True,
                   calibrate: bool = True, progress=None, cancel=None) -> tuple[Fitted, list[Fitted]]:
    """Fit the ``k`` best of ``ranking`` (``rank_graphs``' entries) to the photo of ``loss`` under
    one shared budget of ``schedule`` (see the module docstring) and return ``(best, fitted)``:
    ``Fitted`` records, ``best.material`` with its fitted parameters set. ``materials``: the
    graphs ``rank_graphs`` loaded, by name (others are loaded). ``zoom``: every candidate's,
    fixed (None: each searches its own); ``lighting``: solve each one's falloff, ``calibrate``: its
    gain (``frame_start``).
    ``loss.camera`` is left at the kept candidate's camera. ``progress`` gets {"graph",
    "graph_index", "graph_count", "iteration", "iterations", "loss", "eta_seconds"};
    ``cancel()`` raises Cancelled."""
    if k < 1:
        raise OptionError(f"k must be at least 1, got {k}")
    chosen = ranking[:k]
    device = loss.photo.device
    total = max(len(chosen), round(schedule.iterations * budget_factor(len(chosen))))
    probe = max(1, round(schedule.iterations * PROBE_SHARE)) if len(chosen) > 1 else 0
    state = {"done": 0}
    fits = [Fitted(e["graph"], load_material(e["graph"], device, materials), e["start"], e["distance"], e["nodes"],
                   e["params"]) for e in chosen]
    for f, e in zip(fits, chosen):
        f.camera = frame_start(f.material, loss, e["theta"], schedule, seed, zoom, lighting, calibrate)

    def run(f: Fitted, index: int, sched: Schedule, theta0) -> None:
        def on_step(event):
            state["done"] += 1
            if progress is not None:
                progress({"graph": f.graph, "graph_index": index + 1, "graph_count": len(fits),
                          "iteration": state["done"], "iterations": total, "loss": event["loss"],
                          "eta_seconds": event["eta_seconds"]})

        loss.camera = f.camera
        result = fit(f.material, loss, sched, seed=seed, theta0=theta0, progress=on_step, cancel=cancel)
        f.result = result
        f.iterations += result.iterations
        f.seconds += result.seconds
        last = sched.stages[-1]
        f.rounds.append({"schedule": sched.name, "iterations": result.iterations,
                         "loss_final": round(result.loss_final, 6),
                         "measured_at": {"size": last.size, "scales": list(last.scales), "crop": last.crop}})

    def judged(i: int) -> float:
        return fits[i].fitted.loss_final * (1 + RANK_MARGIN) ** i

    survivors = list(range(len(fits)))
    if probe:
        sched = probe_schedule(schedule, probe)
        for i, f in enumerate(fits):
            run(f, i, sched, chosen[i]["theta"])
        best = min(judged(i) for i in survivors)
        ordered = sorted(survivors, key=judged)
        keep = max(1, math.ceil(len(fits) / 2))
        survivors = [i for i in ordered[:keep] if judged(i) <= best * (1 + DROP_MARGIN)]
        for i, f in enumerate(fits):
            f.survived_probe = i in survivors
    left = total - state["done"]
    share = max(1, left // len(survivors))
    main = schedule.scaled(share) if share != schedule.iterations else schedule
    for i in survivors:
        f = fits[i]
        start = f.result.theta if f.result is not None else chosen[i]["theta"]
        run(f, i, main, start)
    finals = [{"index": i, "loss": judged(i), "nodes": fits[i].nodes, "params": fits[i].params} for i in survivors]
    winner = fits[order_by_simplicity(finals, key="loss")[0]["index"]]
    winner.material.set_vector(winner.fitted.theta)
    winner.material.clear_cache()
    loss.camera = winner.camera
    return winner, fits
