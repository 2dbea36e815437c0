"""The scale at which a graph meets a photo: a search of the calibration's zoom over octaves.

A photo shows its material at a scale nobody told us, and a graph's features have the scale its
author gave them: a fit started at the wrong scale must bend the graph's own scale parameters
(often discrete, so never optimised) or its structure to make up for it. ``search_zoom`` renders
the fit's start framed at every zoom of ``ZOOMS`` (texture periods across the photo; octaves,
because the graph evaluates at power-of-two sizes) and keeps the zoom with the lowest descriptor
loss. The search only zooms out: zooming in evaluates the graph at four times the pixels for
every step of the fit (a balanced fit would pass its four minutes), and where a photo's features
are larger than the graph's, its own scale parameters are the cheaper lever; ``--zoom 0.5``
still asks for it. The authored scale (zoom 1) is kept unless another zoom lowers the loss by
more than ``KEEP_AUTHORED``: the loss of a start is a noisy judge, and a graph's defaults were
chosen for a sample of about the size a phone photographs.

The zoom is then fixed for the fit (``calibration.framed_maps``); in Blender it is the Mapping
node's scale, so the written maps stay one seamless period.
"""
from __future__ import annotations

import torch

from ..vocabulary import ZOOM
from .optim import TargetLoss

ZOOMS = (1.0, 2.0, 4.0)
KEEP_AUTHORED = 0.05


def search_zoom(graph, loss: TargetLoss, theta: torch.Tensor, size: int, scales: tuple[int, ...], seed: int = 0,
                zooms: tuple[float, ...] = ZOOMS) -> dict[float, float]:
    """Set ``graph``'s zoom to the one of ``zooms`` whose framed render of the parameters
    ``theta`` (P,) has the lowest ``loss`` at ``size`` px described at ``scales`` (see the module
    docstring); returns the loss at each zoom."""
    losses = {}
    with torch.no_grad():
        for zoom in zooms:
            graph.calibration.set_values(**{ZOOM: zoom})
            losses[zoom] = float(loss(graph, theta.reshape(1, -1), size, scales, seed)[0])
    best = min(losses, key=losses.__getitem__)
    if 1.0 in losses and losses[best] > losses[1.0] * (1 - KEEP_AUTHORED):
        best = 1.0
    graph.calibration.set_values(**{ZOOM: best})
    return losses
