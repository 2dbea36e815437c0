"""The start of a named library graph's fit: the best of its default parameters and what its
models (predictor, bank) propose, by the loss at the schedule's first stage."""
from __future__ import annotations

import torch

from ..diffmat.optim import Schedule, TargetLoss
from ..library import library_names
from .descriptor import DESCRIPTOR_SIZE, compact_descriptor, shared_vgg
from .rank import best_finite, propose_starts


def choose_start(graph, name: str | None, loss: TargetLoss, schedule: Schedule, seed: int = 0,
                 directory=None) -> tuple[torch.Tensor | None, str]:
    """(theta0 or None, "default" | "predicted" | "bank"): the best by the loss at the schedule's
    first stage of the default and what the models of library graph ``name`` propose (when
    current; "default" for any other graph). The graph is left unchanged."""
    if name is None or name not in library_names():
        return None, "default"
    device = next(loss.descriptor.parameters()).device
    with torch.no_grad():
        descriptor = compact_descriptor(shared_vgg(device), loss.photo.to(device), DESCRIPTOR_SIZE)
    proposals = propose_starts(name, graph, descriptor, "both", directory)
    if not proposals:
        return None, "default"
    first = schedule.stages[0]
    thetas = torch.stack([t.to(device) for _, t in proposals])
    with torch.no_grad():
        losses = loss(graph, thetas, first.size, first.scales, seed, first.crop).cpu()
    best = best_finite(losses)
    if proposals[best][0] == "default":
        return None, "default"
    return proposals[best][1], proposals[best][0]
