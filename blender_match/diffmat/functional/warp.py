"""Warp family: Warp (displacement along the slope of a gradient image) and Directional Warp
(displacement in one direction, scaled by an intensity image).

Both resample the input with bilinear wrap-around sampling (``sample_wrap``), so the output of
tiling inputs tiles, and both are differentiable in their parameters and in both images.
Distances are in pixels of a 256-pixel image; angles in turns, clockwise on screen from +u.
"""
from __future__ import annotations

import math

import torch

from ..errors import DiffMatError
from .common import check_image, gradient_wrap, image_grid, param4d, sample_wrap

__all__ = ["warp", "directional_warp"]

REF = 256.0


def _on_grid(img: torch.Tensor, like: torch.Tensor) -> torch.Tensor:
    """``img`` resampled (wrap-around, bilinear) to ``like``'s size when the sizes differ."""
    if img.shape[-2:] == like.shape[-2:]:
        return img
    u, v = image_grid(like)
    return sample_wrap(img, u.expand(img.shape[0], -1, -1, -1), v.expand(img.shape[0], -1, -1, -1))


def _scalar(value, like: torch.Tensor, where: str) -> torch.Tensor:
    t = param4d(value, like)
    if t.shape[1] != 1:
        raise DiffMatError(f"{where}: expected one value per batch item, got shape {tuple(t.shape)}")
    return t


def warp(input1: torch.Tensor, inputgradient: torch.Tensor, *, intensity=1.0) -> torch.Tensor:
    """Substance's Warp: move the input's content along the slope of ``inputgradient``.

    out(p) = input1(p + k ∇g(p)), with ∇g the wrap-around central-difference slope of the
    (grayscale) gradient image in value per image width and k = ``intensity`` / 256, i.e. a ramp
    rising by 1 across the image displaces by ``intensity`` pixels of a 256-pixel image. Content
    is pushed down the slope, away from the white areas (the documented behaviour).
    """
    check_image(input1, "warp.input1")
    check_image(inputgradient, "warp.inputgradient", channels=(1,))
    g = _on_grid(inputgradient, input1)
    k = _scalar(intensity, input1, "warp.intensity") / REF
    dx, dy = gradient_wrap(g)
    u, v = image_grid(input1)
    return sample_wrap(input1, u + k * dx, v + k * dy)


def directional_warp(input1: torch.Tensor, inputintensity: torch.Tensor, *, intensity=10.0,
                     warpangle=0.0) -> torch.Tensor:
    """Substance's Directional Warp: move the content by ``intensity`` × the intensity map's
    value, in pixels of a 256-pixel image, in the direction ``warpangle`` (turns, clockwise on
    screen from +u). out(p) = input1(p − (intensity / 256) · m(p) · (cos a, sin a)), so a constant
    map m = 1 is a plain shift by ``intensity`` reference pixels."""
    check_image(input1, "directionalwarp.input1")
    check_image(inputintensity, "directionalwarp.inputintensity", channels=(1,))
    m = _on_grid(inputintensity, input1)
    k = _scalar(intensity, input1, "directionalwarp.intensity") / REF
    a = _scalar(warpangle, input1, "directionalwarp.warpangle") * (2 * math.pi)
    u, v = image_grid(input1)
    d = k * m
    return sample_wrap(input1, u - d * torch.cos(a), v - d * torch.sin(a))
