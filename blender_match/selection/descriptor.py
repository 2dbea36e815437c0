"""The compact texture descriptor that graph selection and parameter prediction work on.

The paper (section 4.2) feeds its per-graph predictors the flattened Gram-matrix descriptor T_G:
64² + 128² + 256² + 512² + 512² = 610k values, so the first fully connected layer of every
predictor alone would hold hundreds of millions of weights (hundreds of MB per graph). We use
instead the first two moments of the same feature maps: per channel, the mean and the standard
deviation over the image of the five VGG19 activations that ``TextureDescriptor`` takes the Gram
matrices of (relu1_2, relu2_2, relu3_4, relu4_4, relu5_4), from the same frozen
``VGG19Features``. That is 2 x (64 + 128 + 256 + 512 + 512) = 2944 values, like the Gram matrix
independent of the image's size and of where features sit (a stationary texture statistic: the
mean is the Gram matrix against a constant channel, the variance its diagonal, centred), and it
is what "adaptive instance normalisation" style transfer matches, so it carries most of what the
style loss sees.

Activations are non-negative and their moments span orders of magnitude between layers and
channels; we take ``log(moment + EPS)`` so that a relative change weighs the same everywhere.
``descriptor_distance`` compares descriptors with each of the five layers weighing the same (the
deep layers have 8x the channels of the first; an unweighted distance would ignore colour).

Images are described at ``DESCRIPTOR_SIZE`` (128) px: renders are made at that size for the
training data and the bank, and a photo is resized to it (antialiased), which is also the
coarsest scale of the fit's style loss.
"""
from __future__ import annotations

import torch

from ..diffmat.descriptor import VGG19Features
from ..diffmat.optim import resize_square

DESCRIPTOR_SIZE = 128
LAYER_CHANNELS = (64, 128, 256, 512, 512)
DESCRIPTOR_DIM = 2 * sum(LAYER_CHANNELS)
EPS = 1e-2
DESCRIPTOR_KIND = f"vgg19-mean-std-log-{DESCRIPTOR_SIZE}px"


def compact_descriptor(vgg: VGG19Features, images: torch.Tensor, size: int = DESCRIPTOR_SIZE) -> torch.Tensor:
    """The (N, DESCRIPTOR_DIM) descriptor of RGB images (N, 3, H, W) in [0, 1], described at
    ``size`` px: per layer, log(mean + EPS) of every channel, then log(std + EPS).
    Differentiable in the images; deterministic for a given device."""
    if images.dim() != 4 or images.shape[1] != 3:
        raise ValueError(f"compact descriptor: expected (N, 3, H, W) RGB images, got {tuple(images.shape)}")
    feats = vgg(resize_square(images, size))
    parts = []
    for f in feats:
        flat = f.flatten(2)
        parts.append(torch.log(flat.mean(dim=2) + EPS))
        parts.append(torch.log(flat.std(dim=2) + EPS))
    return torch.cat(parts, dim=1)


def _dim_weights(device=None) -> torch.Tensor:
    """Per-dimension weights that give each layer (means and stds together) the same share."""
    w = [torch.full((2 * c,), 1.0 / (len(LAYER_CHANNELS) * 2 * c)) for c in LAYER_CHANNELS]
    # the layout is [mean_1, std_1, mean_2, std_2, ...]: each layer's 2c values are contiguous
    return torch.cat(w).to(device)


def descriptor_distance(a: torch.Tensor, b: torch.Tensor) -> torch.Tensor:
    """Layer-balanced mean absolute difference between descriptors a (N, D) and b (M, D): (N, M)."""
    w = _dim_weights(a.device)
    return torch.cdist(a.float() * w, b.float().to(a.device) * w, p=1)


_VGG: dict[str, VGG19Features] = {}


def shared_vgg(device="cpu") -> VGG19Features:
    """One frozen VGG19Features per device for the process (loading takes a fraction of a second,
    but the selection code asks for it from several places)."""
    key = str(torch.device(device))
    if key not in _VGG:
        _VGG[key] = VGG19Features().to(device)
    return _VGG[key]
