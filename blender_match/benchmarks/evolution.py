"""A gradient-free baseline for ``bench accuracy``: a (mu, lambda) evolution strategy in the graph's
normalised parameter space.

Each generation draws ``population`` candidates around the mean (Gaussian, step ``sigma``, clamped
to [0, 1]), renders and describes them in one batch (``graph(theta=(B, P))``), and moves the mean
to the log-weighted average of the ``parents`` best (comma selection: the old mean is not kept).
``sigma`` grows by 1.2 after a generation that beats the best point so far and shrinks by 0.75
otherwise (a one-fifth-rule style adaptation), within [0.01, 0.5]. The result is the best
candidate ever seen, as a ``FitResult`` whose history and snapshots have one entry per generation.
"""
from __future__ import annotations

import math
import time

import torch

from ..diffmat.optim import FitResult
from ..errors import OptionError


def evolve(graph, loss, generations: int, *, population: int = 8, parents: int = 2, sigma: float = 0.15,
           size: int = 128, scales: tuple[int, ...] = (128,), seed: int = 0,
           theta0: torch.Tensor | None = None) -> FitResult:
    """Run ``generations`` generations; ``seed`` is both the graph's noise seed and the sampler's."""
    if generations < 0 or population < 2 or not 1 <= parents <= population:
        raise OptionError(f"evolve: bad settings generations={generations} population={population} parents={parents}")
    device = next(loss.descriptor.parameters()).device
    mean = (graph.get_vector() if theta0 is None else theta0.detach().reshape(-1)).to(device).clamp(0, 1)
    rng = torch.Generator().manual_seed(seed)
    weights = torch.tensor([math.log(parents + 0.5) - math.log(i + 1) for i in range(parents)])
    weights = (weights / weights.sum()).to(device)
    start = time.perf_counter()
    with torch.no_grad():
        best_loss = float(loss(graph, mean[None], size, scales, seed)[0])
    best = mean.clone()
    result = FitResult(theta=best, loss_initial=best_loss, loss_final=best_loss, iterations=0, seconds=0.0)
    for _ in range(generations):
        noise = torch.randn(population, mean.numel(), generator=rng).to(device)
        candidates = (mean[None] + sigma * noise).clamp(0.0, 1.0)
        with torch.no_grad():
            values = loss(graph, candidates, size, scales, seed).detach()
        values = torch.where(torch.isfinite(values), values, torch.full_like(values, math.inf))
        order = torch.argsort(values)
        if math.isfinite(float(values[order[0]])):
            mean = (weights[:, None] * candidates[order[:parents]]).sum(dim=0)
        generation_best = float(values[order[0]])
        if generation_best < best_loss:
            best_loss, best = generation_best, candidates[order[0]].clone()
            sigma = min(0.5, sigma * 1.2)
        else:
            sigma = max(0.01, sigma * 0.75)
        result.iterations += 1
        now = time.perf_counter() - start
        result.history.append((now, result.iterations, generation_best))
        result.snapshots.append((now, best.detach().cpu().clone()))
    result.theta = best.detach().cpu()
    result.loss_final = best_loss
    result.seconds = time.perf_counter() - start
    result.stage_seconds = [result.seconds]
    return result
