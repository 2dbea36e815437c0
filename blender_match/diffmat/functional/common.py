"""Tensor helpers shared by the functional ops: input checks, parameter broadcasting, and the
wrap-around (tiling) primitives every node builds on.

Conventions (see docs/engine.md):
- images are NCHW float tensors; C is 1 (grayscale) or 4 (colour, RGBA); values in [0, 1];
- a continuous parameter is a Python number, a sequence, or a tensor of shape (), (k,) or (B, k);
  ``param4d`` turns any of them into a (B|1, k, 1, 1) tensor that broadcasts against an image;
- every spatial op wraps around the image edges, so outputs tile seamlessly.
"""
from __future__ import annotations

import math
from typing import Collection, Sequence

import torch
import torch.nn.functional as F

from ..errors import DiffMatError

GRAY, COLOR = 1, 4


def check_image(x: torch.Tensor, name: str = "input", channels: Sequence[int] = (GRAY, COLOR)) -> torch.Tensor:
    """Raise DiffMatError unless ``x`` is an NCHW float image with an allowed channel count."""
    if not isinstance(x, torch.Tensor):
        raise DiffMatError(f"{name}: expected an image tensor, got {type(x).__name__}")
    if x.dim() != 4:
        raise DiffMatError(f"{name}: expected an NCHW image tensor, got shape {tuple(x.shape)}")
    if x.shape[1] not in channels:
        allowed = " or ".join(str(c) for c in channels)
        raise DiffMatError(f"{name}: expected {allowed} channels, got {x.shape[1]}")
    if not x.is_floating_point():
        raise DiffMatError(f"{name}: expected a float tensor, got {x.dtype}")
    return x


def check_size(size: int, name: str = "size") -> int:
    """Raise DiffMatError unless ``size`` is a power of two between 1 and 16384."""
    if isinstance(size, bool) or not isinstance(size, int) or size < 1 or size > 16384 or size & (size - 1):
        raise DiffMatError(f"{name}: {size!r} is not a power-of-two size between 1 and 16384")
    return size


def check_choice(value, choices: Collection, name: str):
    """Raise DiffMatError unless ``value`` is one of ``choices``."""
    if value not in choices:
        raise DiffMatError(f"{name}: unknown value {value!r}; expected one of {list(choices)}")
    return value


def check_bool(value, name: str) -> bool:
    """``value`` as a bool; raise DiffMatError unless it is 0, 1, True or False (a library node's
    boolean parameter, named ``name`` in the message)."""
    if value in (0, 1, True, False):
        return bool(value)
    raise DiffMatError(f"{name}: expected a boolean, got {value!r}")


def broadcast_shape(*shapes: Sequence[int]) -> tuple[int, ...]:
    """The broadcast of ``shapes``, as ``torch.broadcast_shapes`` computes it; written here
    because torch's version imports sympy on first use (close to a second per process)."""
    ndim = max(len(s) for s in shapes)
    out = []
    for dims in zip(*((1,) * (ndim - len(s)) + tuple(s) for s in shapes)):
        sizes = {d for d in dims if d != 1}
        if len(sizes) > 1:
            raise DiffMatError(f"shapes {[tuple(s) for s in shapes]} do not broadcast together")
        out.append(sizes.pop() if sizes else 1)
    return tuple(out)


def param4d(value, like: torch.Tensor | None = None) -> torch.Tensor:
    """A parameter as a (B|1, k, 1, 1) tensor on ``like``'s device and dtype.

    Accepts a number, a sequence, or a tensor of shape (), (k,), (B, k) or (B, k, 1, 1).
    """
    t = value if isinstance(value, torch.Tensor) else torch.tensor(value, dtype=torch.float32)
    if like is not None:
        t = t.to(device=like.device, dtype=like.dtype)
    if t.dim() == 0:
        return t.reshape(1, 1, 1, 1)
    if t.dim() == 1:
        return t.reshape(1, -1, 1, 1)
    if t.dim() == 2:
        return t.reshape(t.shape[0], t.shape[1], 1, 1)
    if t.dim() == 4:
        return t
    raise DiffMatError(f"parameter: cannot broadcast a tensor of shape {tuple(t.shape)} against an image")


def param2d(value, like: torch.Tensor | None = None) -> torch.Tensor:
    """A parameter as a (B|1, k) tensor (for matrices, vectors, colours)."""
    return param4d(value, like).flatten(1)


def expand_batch(out: torch.Tensor, *params) -> torch.Tensor:
    """Expand ``out`` to the batch size of (B, k) parameters that do not otherwise enter the
    computation, so a batch of B parameter sets always gives B outputs."""
    b = max([out.shape[0]] + [param4d(p).shape[0] for p in params])
    return out.expand(b, -1, -1, -1) if b != out.shape[0] else out


def to_color(x: torch.Tensor) -> torch.Tensor:
    """Grayscale (N,1,H,W) to RGBA (alpha 1); colour passes through."""
    if x.shape[1] == COLOR:
        return x
    return torch.cat([x, x, x, torch.ones_like(x)], dim=1)


def to_gray(x: torch.Tensor) -> torch.Tensor:
    """RGBA to grayscale by the mean of RGB (Substance's default weights); gray passes through."""
    if x.shape[1] == GRAY:
        return x
    return x[:, :3].mean(dim=1, keepdim=True)


def match_channels(x: torch.Tensor, channels: int) -> torch.Tensor:
    """Convert ``x`` to ``channels`` (1 or 4) channels."""
    return to_color(x) if channels == COLOR else to_gray(x)


def image_grid(like: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
    """Pixel-centre coordinates (u, v) in [0, 1) of ``like``'s H x W pixels, each (1, 1, H, W)."""
    h, w = like.shape[-2:]
    cu = (torch.arange(w, device=like.device, dtype=like.dtype) + 0.5) / w
    cv = (torch.arange(h, device=like.device, dtype=like.dtype) + 0.5) / h
    v, u = torch.meshgrid(cv, cu, indexing="ij")
    return u[None, None], v[None, None]


def pixel_grid(size: int, device=None, dtype=torch.float32) -> tuple[torch.Tensor, torch.Tensor]:
    """Pixel-centre coordinates (u, v) in [0, 1), each (1, 1, size, size); u grows rightwards, v downwards."""
    c = (torch.arange(size, device=device, dtype=dtype) + 0.5) / size
    v, u = torch.meshgrid(c, c, indexing="ij")
    return u[None, None], v[None, None]


def sample_wrap(img: torch.Tensor, u: torch.Tensor, v: torch.Tensor, mode: str = "bilinear") -> torch.Tensor:
    """Sample ``img`` at texture coordinates (u, v) with wrap-around addressing.

    ``u`` and ``v`` are (B, H, W) or (B, 1, H, W) in texture units (1 = one image width); any value
    is folded into [0, 1). Bilinear sampling across the seam reads the opposite edge, so a warp or
    transform of a tiling image tiles. Differentiable in the image and in (u, v).

    Grayscale images go through ``grid_sample`` (fast for one channel); colour images through
    four gathers shared by the channels (``grid_sample``'s CPU backward is slow for several
    channels). Both are the same bilinear interpolation.
    """
    if u.dim() == 4:
        u, v = u[:, 0], v[:, 0]
    n, c, h, w = img.shape
    if mode == "bilinear" and c > 1 and torch.is_grad_enabled() and (
            img.requires_grad or u.requires_grad or v.requires_grad):
        # grid_sample's CPU backward is slow for several channels; its forward is ~3x faster
        # than the gathers, so it serves every evaluation that needs no gradient
        return _bilinear_gather(img, u, v)
    b = max(n, u.shape[0])
    padded = F.pad(img, (1, 1, 1, 1), mode="circular")
    # fold into [0, 1) (u - floor(u): torch.remainder is several times slower on CPU), then map
    # texel i (centre (i + 0.5) / w, at i + 1 in the padded image) to grid_sample's [-1, 1]:
    # g = (u w + 0.5) / (w + 1) * 2 - 1, one multiply-add.
    grid = torch.stack([u, v], dim=-1)
    grid = grid - torch.floor(grid.detach())
    scale, shift = grid_affine(w, h, img.device, img.dtype)
    grid = torch.addcmul(shift, grid, scale)
    if padded.shape[0] != b:
        padded = padded.expand(b, -1, -1, -1)
    if grid.shape[0] != b:
        grid = grid.expand(b, -1, -1, -1)
    return F.grid_sample(padded, grid, mode=mode, padding_mode="border", align_corners=True)


_AFFINE_CACHE: dict = {}


def grid_affine(w: int, h: int, device, dtype) -> tuple[torch.Tensor, torch.Tensor]:
    """(scale, shift), each (2,), mapping wrapped texture coordinates in [0, 1) of a w x h image
    to ``grid_sample``'s [-1, 1] on that image padded by one texel each side (align_corners):
    g = u * scale + shift. Cached per size, device and dtype."""
    key = (w, h, str(device), dtype)
    hit = _AFFINE_CACHE.get(key)
    if hit is None:
        scale = torch.tensor([2.0 * w / (w + 1), 2.0 * h / (h + 1)], dtype=dtype, device=device)
        shift = torch.tensor([1.0 / (w + 1) - 1.0, 1.0 / (h + 1) - 1.0], dtype=dtype, device=device)
        hit = _AFFINE_CACHE[key] = (scale, shift)
    return hit


def _bilinear_gather(img: torch.Tensor, u: torch.Tensor, v: torch.Tensor) -> torch.Tensor:
    """Bilinear wrap-around sampling by gathering the four neighbours (power-of-two sizes: the
    wrap is a bit mask). ``u``, ``v`` are (B, H', W')."""
    n, c, h, w = img.shape
    b = max(n, u.shape[0])
    oh, ow = u.shape[-2:]
    w1 = w + 1
    padded = F.pad(img, (0, 1, 0, 1), mode="circular")           # (h + 1, w + 1): x0 + 1 never wraps
    x = u * w - 0.5                                                  # pixel coordinates, centres at integers
    y = v * h - 0.5
    x0 = torch.floor(x.detach())
    y0 = torch.floor(y.detach())
    fx = (x - x0)[:, None]
    fy = (y - y0)[:, None]
    base = (y0.long() & (h - 1)) * w1 + (x0.long() & (w - 1))
    base = base.reshape(base.shape[0], 1, oh * ow)
    if base.shape[0] != b:
        base = base.expand(b, -1, -1)
    flat = padded.reshape(n, c, (h + 1) * w1)
    if n != b:
        flat = flat.expand(b, -1, -1)

    def corner(offset: int) -> torch.Tensor:
        idx = base + offset if offset else base
        return torch.gather(flat, 2, idx.expand(-1, c, -1)).reshape(b, c, oh, ow)

    top = torch.lerp(corner(0), corner(1), fx)
    bottom = torch.lerp(corner(w1), corner(w1 + 1), fx)
    return torch.lerp(top, bottom, fy)


def frequencies(size: int, device=None, dtype=torch.float32) -> tuple[torch.Tensor, torch.Tensor]:
    """FFT frequency grids (fx, fy) in cycles per image width, shaped for ``torch.fft.rfft2`` output."""
    fy = torch.fft.fftfreq(size, d=1.0 / size, device=device, dtype=dtype)
    fx = torch.fft.rfftfreq(size, d=1.0 / size, device=device, dtype=dtype)
    return fx[None, :].expand(size, -1), fy[:, None].expand(-1, fx.shape[0])


def fft_filter(img: torch.Tensor, transfer: torch.Tensor) -> torch.Tensor:
    """Circular convolution by a real transfer function given on the ``rfft2`` grid.

    ``transfer`` broadcasts against (N, C, H, W//2+1). Circular, so the result tiles; the cost does
    not depend on the kernel's radius, and the transfer function may depend differentiably on
    parameters (a blur's radius, a direction).
    """
    spec = torch.fft.rfft2(img)
    return torch.fft.irfft2(spec * transfer, s=img.shape[-2:])


def gaussian_blur(img: torch.Tensor, sigma, sigma_y=None, angle=None) -> torch.Tensor:
    """Wrap-around Gaussian blur; ``sigma`` in texture units (fraction of the image width).

    With ``sigma_y`` and ``angle`` (turns) the kernel is anisotropic: ``sigma`` along the direction
    ``angle``, ``sigma_y`` across it. Parameters may be tensors (B, 1); differentiable in all of them.
    """
    size = img.shape[-1]
    fx, fy = frequencies(size, img.device, img.dtype)
    s = param4d(sigma, img)
    if sigma_y is None:
        transfer = torch.exp(-2 * math.pi ** 2 * s ** 2 * (fx ** 2 + fy ** 2))
    else:
        a = param4d(angle if angle is not None else 0.0, img) * 2 * math.pi
        along = fx * torch.cos(a) + fy * torch.sin(a)
        across = -fx * torch.sin(a) + fy * torch.cos(a)
        sy = param4d(sigma_y, img)
        transfer = torch.exp(-2 * math.pi ** 2 * (s ** 2 * along ** 2 + sy ** 2 * across ** 2))
    return fft_filter(img, transfer)


def gradient_wrap(img: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
    """Central-difference slopes (d/du, d/dv) in value per texture unit, wrapping around the edges."""
    size = img.shape[-1]
    if img.dim() != 4:
        dx = (torch.roll(img, -1, dims=-1) - torch.roll(img, 1, dims=-1)) * (size / 2)
        dy = (torch.roll(img, -1, dims=-2) - torch.roll(img, 1, dims=-2)) * (size / 2)
        return dx, dy
    # one circular pad and the four neighbours as strided views (no roll copies); same values
    h, w = img.shape[-2:]
    p = F.pad(img, (1, 1, 1, 1), mode="circular")
    dx = torch.sub(p[..., 1:h + 1, 2:], p[..., 1:h + 1, :w]).mul_(size / 2)
    dy = torch.sub(p[..., 2:, 1:w + 1], p[..., :h, 1:w + 1]).mul_(size / 2)
    return dx, dy


def step(x: torch.Tensor) -> torch.Tensor:
    """Float mask 1 where x >= 0, 0 where x < 0, built from arithmetic (on CPU, comparisons,
    ``where`` and their backward passes are several times slower than a multiply). No gradient."""
    with torch.no_grad():
        return torch.sign(x).add_(1.0).clamp_(max=1.0).ceil_()   # -1 -> 0, 0 -> 1, 1 -> 1


def lerp(a: torch.Tensor, b: torch.Tensor, w) -> torch.Tensor:
    """a + w (b - a), broadcasting ``w``."""
    return a + (b - a) * w
