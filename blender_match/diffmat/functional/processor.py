"""Pixel Processor and Value Processor: Substance's programmable nodes, evaluated through the
function-graph evaluator (``function_graph.py``); each function graph is compiled once per
JSON text (``function_graph.compiled``).

- ``pixel_processor`` runs a function graph once per pixel: ``$pos`` is the pixel centre in [0, 1)²,
  ``samplelum``/``samplecol`` read the node's inputs (index 0 = ``input``, 1 = ``input_1``, ...)
  with wrap-around addressing. The result (1 to 4 components) becomes a grayscale image (first
  component) or, with ``colorswitch``, an RGBA image (a scalar is spread to RGB with alpha 1; a
  2- or 3-vector gets B = 0 / alpha 1). Values are clamped to [0, 1] (8/16-bit output formats).
  The output has the size of the first connected input, or the context size without one.
- ``value_processor`` evaluates a function graph once. A MaterialGraph carries images only, so a
  value output that must flow into an image slot becomes a uniform image of that value (grayscale
  for a scalar, RGBA otherwise, clamped to [0, 1]); the translator otherwise evaluates value
  processors at translation time and substitutes them into the function graphs that read them.
"""
from __future__ import annotations

import math

import torch

from ..errors import DiffMatError
from .function_graph import compiled

__all__ = ["pixel_processor", "value_processor", "DEFAULT_PERPIXEL", "DEFAULT_VALUE_FUNCTION"]

DEFAULT_PERPIXEL = ('{"nodes":{"c":{"data":[0.0,0.0,0.0,1.0],"function":"const_float4","inputs":{}}},'
                    '"root":"c"}')
DEFAULT_VALUE_FUNCTION = '{"nodes":{"c":{"data":0.0,"function":"const_float1","inputs":{}}},"root":"c"}'


def _system_variables(h: int, w: int, device, dtype) -> dict:
    return {"$size": torch.tensor([float(w), float(h)], device=device, dtype=dtype),
            "$sizelog2": torch.tensor([math.log2(w), math.log2(h)], device=device, dtype=dtype),
            "$normalformat": torch.zeros(1, device=device, dtype=dtype),
            "$time": torch.zeros(1, device=device, dtype=dtype)}


def _to_channels(v: torch.Tensor, color: bool) -> torch.Tensor:
    """(..., k) -> (..., 4) RGBA or (..., 1) gray."""
    k = v.shape[-1]
    if not color:
        return v[..., :1]
    one = torch.ones_like(v[..., :1])
    if k == 1:
        return torch.cat([v, v, v, one], dim=-1)
    if k == 2:
        return torch.cat([v, torch.zeros_like(one), one], dim=-1)
    if k == 3:
        return torch.cat([v, one], dim=-1)
    return v[..., :4]


def pixel_processor(*images, perpixel: str = DEFAULT_PERPIXEL, colorswitch: bool = True, size: int = 512,
                    seed: int = 0, device=None, dtype=torch.float32) -> torch.Tensor:
    """Evaluate the function graph ``perpixel`` (JSON text) at every pixel; returns (N, 1|4, H, W)."""
    evaluate = compiled(perpixel)
    connected = [im for im in images if im is not None]
    if connected:
        h, w = connected[0].shape[-2:]
        device, dtype = connected[0].device, connected[0].dtype
    else:
        h = w = size
    cy = (torch.arange(h, device=device, dtype=dtype) + 0.5) / h
    cx = (torch.arange(w, device=device, dtype=dtype) + 0.5) / w
    y, x = torch.meshgrid(cy, cx, indexing="ij")
    variables = _system_variables(h, w, device, dtype)
    variables["$pos"] = torch.stack([x, y], dim=-1)[None]  # (1, H, W, 2)
    value = evaluate(variables, images=list(images), seed=seed, device=device, dtype=dtype)
    if isinstance(value, str):
        raise DiffMatError("pixelprocessor: the function returns a string")
    value = _to_channels(value, bool(colorswitch))
    while value.dim() < 4:
        value = value.unsqueeze(0)
    value = value.expand(value.shape[0], h, w, value.shape[-1])
    return value.permute(0, 3, 1, 2).clamp(0.0, 1.0)


def value_processor(*, function: str = DEFAULT_VALUE_FUNCTION, size: int = 512, seed: int = 0, device=None,
                    dtype=torch.float32) -> torch.Tensor:
    """Evaluate ``function`` (JSON text) once; returns a uniform (B|1, 1|4, size, size) image of it."""
    evaluate = compiled(function)
    value = evaluate(_system_variables(size, size, device, dtype), seed=seed, device=device, dtype=dtype)
    if isinstance(value, str):
        raise DiffMatError("valueprocessor: the function returns a string")
    value = value.reshape(-1, value.shape[-1]) if value.dim() > 1 else value[None]
    value = _to_channels(value, value.shape[-1] > 1)
    return value[:, :, None, None].expand(-1, -1, size, size).clamp(0.0, 1.0)
