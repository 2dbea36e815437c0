"""The methods ``bench accuracy`` compares, each run at several budgets (iteration counts).

- ``paper``: the paper's optimiser (Adam 5e-4, the 512/256/128 descriptor every step,
  ``PAPER_SCHEDULE``) from the default parameters;
- ``draft``, ``balanced``, ``best``: our quality schedules (``QUALITY_SCHEDULES``) from the default
  parameters, each rescaled to the budget (``Schedule.scaled``);
- ``predict``: the parameter predictor's guess alone (no optimisation; one point);
- ``predict+ours`` and ``bank+ours``: the balanced schedule started from the predictor's guess or
  the nearest neighbour of the photo in the parameter bank;
- ``es``: a gradient-free (mu, lambda) evolution strategy at 128 px (``evolution.evolve``).

The paper's optimiser has a constant learning rate and the evolution strategy no schedule, so a
shorter budget is exactly a prefix of the longest run: both run once and every budget is read from
the run's history. Our schedules depend on their length and run once per budget, unless ``prefix``
is asked for (``--quick``) and every stage of the capped schedule renders and describes alike: then
each budget is what the longest run had found after that many iterations (its anytime curve).
Schedules are capped at the benchmark's evaluation size (``cap_schedule``).

Prediction goes through ``Selection``, an adapter to ``blender_match.selection`` that reports the
method unavailable when the graph's models are missing.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import torch

from ..diffmat.optim import PAPER_SCHEDULE, QUALITY_SCHEDULES, Schedule, fit
from ..errors import OptionError
from ..selection import NoSelectionModels, rank_graphs
from .accuracy_metrics import cap_scales
from .evolution import evolve
from .measure import measure

METHODS = ("paper", "predict", "predict+ours", "bank+ours", "draft", "balanced", "best", "es")
REFINE_PRESET = "balanced"  # the schedule that refines a predicted start


def cap_schedule(schedule: Schedule, cap: int) -> Schedule:
    """``schedule`` with every stage's render size and descriptor scales at most ``cap`` px."""
    stages = tuple(replace(s, size=min(s.size, cap), scales=cap_scales(s.scales, cap)) for s in schedule.stages)
    return Schedule(schedule.name, stages, schedule.patience, schedule.min_improvement)


@dataclass
class Point:
    """One method's result at one budget: the parameters found, wall seconds and iterations to
    find them (prediction time included), the peak memory of the run that produced them."""

    budget: int
    theta: torch.Tensor
    seconds: float
    iterations: int
    peak_bytes: int
    start: torch.Tensor
    history: list = field(default_factory=list)
    offset: float = 0.0  # seconds spent before the fit's clock started (the prediction)


class Unavailable(Exception):
    """A method that cannot run here (its module or model files are missing)."""


class Selection:
    """Adapter to the selection module (the per-graph parameter predictors and the sample bank):
    ``start(photo, graph_name, method)`` -> (theta, seconds), the start ``rank_graphs`` proposes
    for that one graph (``method`` "predictor" or "bank"), or raises ``Unavailable`` when the
    graph's model files are missing. Cached per photo."""

    def __init__(self, device: str = "cpu"):
        self.device = device
        self._cache: dict = {}

    def _rank(self, photo: torch.Tensor, method: str, graph_name: str):
        try:
            return rank_graphs(photo, method=method, graphs=[graph_name], device=self.device)
        except FileNotFoundError as exc:
            raise Unavailable(f"{method}: model files missing ({exc})") from None
        except NoSelectionModels:
            raise Unavailable(f"{method}: no model for {graph_name}") from None

    def start(self, photo: torch.Tensor, graph_name: str, method: str) -> tuple[torch.Tensor, float]:
        key = (id(photo), method, graph_name)
        if key not in self._cache:
            began = time.perf_counter()
            try:
                ranking = self._rank(photo, method, graph_name)
            except Unavailable as exc:
                ranking = exc
            # the photo is kept with its ranking, so that its id cannot be reused by another photo
            self._cache[key] = (photo, ranking, time.perf_counter() - began)
        _, ranking, seconds = self._cache[key]
        if isinstance(ranking, Unavailable):
            raise ranking
        for entry in ranking:
            if entry.get("graph") == graph_name and entry.get("theta") is not None:
                theta = torch.as_tensor(entry["theta"], dtype=torch.float32).reshape(-1).cpu()
                return theta, seconds
        raise Unavailable(f"{method}: no prediction for graph {graph_name}")


def _prefix_points(result, start: torch.Tensor, budgets, peak: int, evaluated_points: bool,
                   extra_seconds: float = 0.0) -> list[Point]:
    """Points of a run's prefixes. ``evaluated_points``: history[i] holds the loss of the point the
    i-th step started from (``fit``), and a run of b steps returns the best of the first b (or
    the start); otherwise each snapshot already is the best so far (``evolve``). A budget past a
    run that stopped early (plateau) gets the whole run."""
    points = []
    for budget in sorted(budgets):
        b = min(budget, len(result.history))
        if b == 0:
            points.append(Point(budget, start, extra_seconds, 0, peak, start))
            continue
        if evaluated_points:
            losses = [h[2] for h in result.history[:b]]
            j = min(range(b), key=lambda i: (losses[i] if losses[i] == losses[i] else float("inf"), i))
            theta = start if j == 0 else result.snapshots[j - 1][1]
        else:
            theta = result.snapshots[b - 1][1]
        points.append(Point(budget, theta.detach().cpu(), result.history[b - 1][0] + extra_seconds, b, peak, start,
                            result.history[:b], extra_seconds))
    return points


def _uniform(schedule: Schedule) -> bool:
    """Whether every stage renders at one size and describes at one set of scales (so losses of
    different stages compare)."""
    return len({(s.size, s.scales) for s in schedule.stages}) == 1


def _run_schedule(graph, loss, schedule, budgets, cap, seed, start, extra_seconds, device, prefix) -> list[Point]:
    longest = cap_schedule(schedule.scaled(max(budgets)), cap)
    if not (prefix and _uniform(longest)):
        return [_fit_point(graph, loss, schedule, b, cap, seed, start, extra_seconds, device) for b in budgets]
    with measure(device) as m:
        result = fit(graph, loss, longest, seed=seed, theta0=start, keep_snapshots=True)
    return _prefix_points(result, start, budgets, m.peak_bytes, evaluated_points=True, extra_seconds=extra_seconds)


def _schedule_of(method: str) -> Schedule | None:
    """The gradient schedule ``method`` runs (None: prediction only, or the evolution strategy)."""
    if method == "paper":
        return PAPER_SCHEDULE
    if method in QUALITY_SCHEDULES:
        return QUALITY_SCHEDULES[method]
    if method.endswith("+ours"):
        return QUALITY_SCHEDULES[REFINE_PRESET]
    return None


def fit_sizes(methods, cap: int) -> set[tuple[int, tuple[int, ...]]]:
    """(size, scales) every fit of ``methods`` renders and describes at (for warming caches up)."""
    out: set[tuple[int, tuple[int, ...]]] = set()
    for method in methods:
        if method == "es":
            out.add((min(128, cap), (min(128, cap),)))
        elif (schedule := _schedule_of(method)) is not None:
            out |= {(s.size, s.scales) for s in cap_schedule(schedule, cap).stages}
    return out


def run_method(method: str, graph, loss, budgets, *, cap: int, seed: int = 0, default: torch.Tensor,
               photo: torch.Tensor | None = None, graph_name: str = "", selection: Selection | None = None,
               device: str = "cpu", es_population: int = 8, prefix: bool = False) -> list[Point]:
    """Run ``method`` on ``graph`` against ``loss`` at each budget; raises ``Unavailable``."""
    budgets = sorted(set(int(b) for b in budgets))
    if method == "paper":
        with measure(device) as m:
            result = fit(graph, loss, cap_schedule(PAPER_SCHEDULE.scaled(max(budgets)), cap), seed=seed,
                         theta0=default, keep_snapshots=True)
        return _prefix_points(result, default, budgets, m.peak_bytes, evaluated_points=True)
    if method == "es":
        size = min(128, cap)
        with measure(device) as m:
            result = evolve(graph, loss, max(budgets), population=es_population, size=size, scales=(size,),
                            seed=seed, theta0=default)
        return _prefix_points(result, default, budgets, m.peak_bytes, evaluated_points=False)
    if method in QUALITY_SCHEDULES:
        return _run_schedule(graph, loss, _schedule_of(method), budgets, cap, seed, default, 0.0, device, prefix)
    if method in ("predict", "predict+ours", "bank+ours"):
        if photo is None:
            raise Unavailable(f"{method}: predicting a start needs the target's photo")
        selection = selection or Selection(device)
        kind = "bank" if method.startswith("bank") else "predictor"
        with measure(device) as m:
            start, seconds = selection.start(photo, graph_name, kind)
        start = start.clamp(0, 1)
        if start.numel() != default.numel():
            raise Unavailable(f"{method}: {start.numel()} predicted parameters, graph {graph_name} has "
                              f"{default.numel()}")
        if method == "predict":
            return [Point(0, start, seconds, 0, m.peak_bytes, default)]
        return _run_schedule(graph, loss, _schedule_of(method), budgets, cap, seed, start, seconds, device, prefix)
    raise OptionError(f"unknown method {method!r} (methods: {', '.join(METHODS)})")


def _fit_point(graph, loss, schedule, budget, cap, seed, start, extra_seconds, device) -> Point:
    with measure(device) as m:
        result = fit(graph, loss, cap_schedule(schedule.scaled(budget), cap), seed=seed, theta0=start)
    return Point(budget, result.theta, result.seconds + extra_seconds, result.iterations, m.peak_bytes, start,
                 result.history, extra_seconds)
