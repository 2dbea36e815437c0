"""Library (non-atomic) normal, height and relief nodes of Substance's standard library, written
natively: Normal Combine / Blend / Normalise, Normal to Height, Curvature, Curvature Smooth,
HBAO, Ambient Occlusion 2, Edge Detect, Bevel, and the metallic/roughness to
diffuse/specular/glossiness converter.

Normal maps are RGBA, tangent space, encoded n * 0.5 + 0.5. ``normal_format`` 0 is DirectX
(green points down the image), 1 is OpenGL (green points up). Slopes and curvatures are measured
per pixel of a 256-pixel image so results do not depend on the resolution. Spatial work is FFT or
wrap-around sampling, so tiling inputs give tiling outputs.
"""
from __future__ import annotations

import math

import torch

from ..errors import DiffMatError
from .common import (
    COLOR,
    check_bool,
    frequencies,
    gaussian_blur,
    gradient_wrap,
    param4d,
    pixel_grid,
    sample_wrap,
    to_gray,
)
from .distance import distance as distance_fade
from .library_adjust import linear_to_srgb, srgb_to_linear
from .library_blur import blur_hq
from .relief import height_to_normal
from .tone import levels as tone_levels

__all__ = ["normal_combine", "normal_blend", "normal_normalise", "normal_to_height", "curvature",
           "curvature_smooth", "hbao", "ambient_occlusion", "edge_detect", "bevel",
           "metallic_roughness_to_specular_glossiness", "height_to_normal_map"]

PX = 1.0 / 256.0


def _check_format(fmt, name):
    if fmt not in (0, 1):
        raise DiffMatError(f"{name}.normal_format: unknown value {fmt!r}; expected 0 (DirectX) or 1 (OpenGL)")
    return fmt


def _decode(n: torch.Tensor) -> torch.Tensor:
    """RGBA normal map to vectors in [-1, 1]^3 (gray input: a flat normal). Tangent-space normals
    cannot point into the surface, so z is clamped at 0."""
    if n.shape[1] != COLOR:
        flat = torch.zeros(n.shape[0], 3, *n.shape[-2:], dtype=n.dtype, device=n.device)
        flat[:, 2] = 1.0
        return flat
    v = n[:, :3] * 2.0 - 1.0
    return torch.cat([v[:, :2], v[:, 2:].clamp_min(0.0)], dim=1)


def _normalize(v: torch.Tensor) -> torch.Tensor:
    return v / torch.sqrt((v * v).sum(dim=1, keepdim=True) + 1e-12)


def _encode(v: torch.Tensor) -> torch.Tensor:
    half_inv = torch.rsqrt((v * v).sum(dim=1, keepdim=True) + 1e-12) * 0.5     # 1 / (2 |v|)
    rgb = torch.addcmul(v.new_full((), 0.5), v, half_inv).clamp(0.0, 1.0)
    return torch.cat([rgb, torch.ones_like(rgb[:, :1])], dim=1)


def height_to_normal_map(height: torch.Tensor, intensity=1.0, normal_format: int = 0) -> torch.Tensor:
    """Tangent-space normal map of a height map: slopes in height per 256-px pixel times
    ``intensity``; OpenGL or DirectX green."""
    h = to_gray(height)
    du, dv = gradient_wrap(h)
    k = param4d(intensity, h) * PX
    nx = -k * du
    ny = k * dv if normal_format == 1 else -k * dv
    return _encode(torch.cat([nx, ny, torch.ones_like(nx)], dim=1))


def _whiteout_nograd(a: torch.Tensor, b: torch.Tensor) -> torch.Tensor:
    """``normal_combine`` quality 0 on encoded RGBA maps without autograd: the same arithmetic as
    the differentiable path (and ``_encode``), on in-place buffers. What it saves: docs/engine.md,
    "No-grad twins"."""
    with torch.no_grad():
        n = max(a.shape[0], b.shape[0])
        v = torch.empty((n, 3) + tuple(a.shape[-2:]), dtype=a.dtype, device=a.device)
        torch.add(a[:, :2], b[:, :2], out=v[:, :2]).mul_(2.0).sub_(2.0)
        za = (a[:, 2:3] * 2.0).sub_(1.0).clamp_min_(0.0)
        zb = (b[:, 2:3] * 2.0).sub_(1.0).clamp_min_(0.0)
        torch.mul(za, zb, out=v[:, 2:3])
        del za, zb
        half_inv = (v * v).sum(dim=1, keepdim=True).add_(1e-12).rsqrt_().mul_(0.5)
        out = torch.empty((n, 4) + tuple(a.shape[-2:]), dtype=a.dtype, device=a.device)
        torch.addcmul(v.new_full((), 0.5), v, half_inv, out=out[:, :3])
        out[:, :3].clamp_(0.0, 1.0)
        out[:, 3:] = 1.0
        return out


def normal_combine(input: torch.Tensor, input_1: torch.Tensor, *, blend_quality: int = 0):
    """Normal Combine: details of ``input_1`` on top of ``input``. ``blend_quality`` 0 (fast):
    whiteout blending (xy added, z multiplied); 1 (high): reoriented normal mapping. A flat
    ``input_1`` leaves ``input`` unchanged (and vice versa)."""
    if blend_quality not in (0, 1):
        raise DiffMatError(f"normal_combine.blend_quality: unknown value {blend_quality!r}; expected 0 or 1")
    if blend_quality == 0 and input.shape[1] == COLOR and input_1.shape[1] == COLOR:
        # whiteout on the encoded maps directly: xy = (2 a - 1) + (2 b - 1), z = a_z b_z (z >= 0)
        if not torch.is_grad_enabled() or not (input.requires_grad or input_1.requires_grad):
            return _whiteout_nograd(input, input_1)
        xy = (input[:, :2] + input_1[:, :2]) * 2.0 - 2.0
        z = (input[:, 2:3] * 2.0 - 1.0).clamp_min(0.0) * (input_1[:, 2:3] * 2.0 - 1.0).clamp_min(0.0)
        return _encode(torch.cat([xy, z], dim=1))
    a, b = _decode(input), _decode(input_1)
    if blend_quality == 0:
        v = torch.cat([a[:, :2] + b[:, :2], a[:, 2:] * b[:, 2:]], dim=1)
    else:
        t = a + torch.tensor([0.0, 0.0, 1.0], dtype=a.dtype, device=a.device)[None, :, None, None]
        u = b * torch.tensor([-1.0, -1.0, 1.0], dtype=a.dtype, device=a.device)[None, :, None, None]
        v = t * (t * u).sum(1, keepdim=True) / t[:, 2:].clamp_min(1e-4) - u
    return _encode(v)


def normal_blend(normalbg: torch.Tensor, normalfg: torch.Tensor, mask: torch.Tensor | None = None, *,
                 opacity=1.0, use_mask: bool = True):
    """Normal Blend: ``normalfg`` over ``normalbg`` with ``opacity`` (times ``mask`` when connected
    and ``use_mask``), renormalised."""
    a, b = _decode(normalbg), _decode(normalfg)
    w = param4d(opacity, a)
    if mask is not None and check_bool(use_mask, "normal_blend.use_mask"):
        w = w * to_gray(mask)
    return _encode(a + (b - a) * w)


def normal_normalise(input: torch.Tensor):
    """Normal Normalise: rescales every normal to unit length."""
    return _encode(_decode(input))


def _slopes(normal: torch.Tensor, normal_format: int):
    """Height slopes (d/du, d/dv) per 256-px pixel from a normal map."""
    n = _decode(normal)
    nz = n[:, 2:].clamp_min(0.05)
    su = -n[:, 0:1] / nz
    sv = n[:, 1:2] / nz if normal_format == 1 else -n[:, 1:2] / nz
    return su, sv


def _derivative_transfer(size, like):
    """Transfer functions of ``gradient_wrap`` (central differences, per 256-px pixel)."""
    fx, fy = frequencies(size, like.device, like.dtype)
    k = size / 2 * PX * 2
    return k * torch.sin(2 * math.pi * fx / size), k * torch.sin(2 * math.pi * fy / size), fx, fy


def normal_to_height(input: torch.Tensor, *, normal_format: int = 0, relief_balance=(0.5, 0.5, 0.5),
                     opacity=1.0):
    """Normal to Height: integrates the normal map's slopes into a height map (least squares,
    FFT), weights low / mid / high frequencies by ``relief_balance`` (0.5 = neutral; octave bands
    of the image size), scales the relief by ``opacity`` and normalises it to [0, 1] around 0.5."""
    _check_format(normal_format, "normal_to_height")
    su, sv = _slopes(input, normal_format)
    size = input.shape[-1]
    du, dv, fx, fy = _derivative_transfer(size, su)
    spec_u, spec_v = torch.fft.rfft2(su), torch.fft.rfft2(sv)
    den = du * du + dv * dv
    # gradient_wrap's transfer is i * d: least squares H = -i (d_u Su + d_v Sv) / (d_u^2 + d_v^2)
    num = spec_u * du + spec_v * dv
    hspec = -1j * num / den.clamp_min(1e-12) * (den > 1e-9)
    rb = param4d(relief_balance, su)
    f = torch.sqrt(fx * fx + fy * fy).clamp_min(1.0)
    r = (torch.log2(f) / max(math.log2(size / 2), 1.0)).clamp(0.0, 1.0)
    lo, mid, hi = rb[:, 0:1], rb[:, 1:2], rb[:, 2:3]
    band = torch.where(r < 0.5, lo + (mid - lo) * (r * 2), mid + (hi - mid) * (r * 2 - 1)) * 2.0
    h = torch.fft.irfft2(hspec * band, s=input.shape[-2:])
    span = (h.amax(dim=(-2, -1), keepdim=True) - h.amin(dim=(-2, -1), keepdim=True)).clamp_min(1e-6)
    mean = h.mean(dim=(-2, -1), keepdim=True)
    return (0.5 + param4d(opacity, h) * (h - mean) / span).clamp(0.0, 1.0)


def _divergence(normal: torch.Tensor, normal_format: int) -> torch.Tensor:
    """Divergence of the normals' tangent part per 256-px pixel (positive on bumps)."""
    n = _decode(normal)
    ny_up = n[:, 1:2] if normal_format == 1 else -n[:, 1:2]
    dnx, _ = gradient_wrap(n[:, 0:1])
    _, dny = gradient_wrap(ny_up)
    return (dnx - dny) * PX


def curvature(input: torch.Tensor, *, normal_format: int = 0, intensity=1.0):
    """Curvature: 0.5 + ``intensity`` x the divergence of the normal map (per 256-px pixel):
    convex areas bright, concave dark, flat 0.5."""
    _check_format(normal_format, "curvature")
    div = _divergence(input, normal_format)
    return (0.5 + param4d(intensity, div) * div).clamp(0.0, 1.0)


def curvature_smooth(input: torch.Tensor, *, normal_format: int = 0):
    """Curvature Smooth: curvature averaged over Gaussian scales of 1, 2, 4, 8 and 16 pixels
    (of 256), normalised so the strongest curvature reaches 0 or 1 (flat stays 0.5)."""
    _check_format(normal_format, "curvature_smooth")
    div = _divergence(input, normal_format)
    size = div.shape[-1]
    fx, fy = frequencies(size, div.device, div.dtype)
    f2 = fx * fx + fy * fy
    transfer = sum(torch.exp(-2 * math.pi ** 2 * (s * PX) ** 2 * f2) for s in (1, 2, 4, 8, 16)) / 5
    c = torch.fft.irfft2(torch.fft.rfft2(div) * transfer, s=div.shape[-2:])
    peak = c.abs().amax(dim=(-2, -1), keepdim=True).clamp_min(1e-6)
    return (0.5 + 0.5 * c / peak).clamp(0.0, 1.0)


HBAO_STEPS = 2
HBAO_RADIUS = 0.05        # image widths at radius 1
HBAO_HEIGHT = 0.25        # image widths of relief at height_depth 1


def hbao(input: torch.Tensor, *, height_depth=0.1, radius=1.0, quality: int = 4, use_world_units: bool = False,
         surface_size=100.0, height_scale=1.0):
    """HBAO: horizon-based ambient occlusion of a height map (1 unoccluded, darker in cavities).

    Heights span ``height_depth`` x 0.25 image widths (with ``use_world_units``: ``height_scale``
    cm over ``surface_size`` cm). Along ``quality`` directions (4, 8 or 16; at most 8 are
    traced), 2 steps out to ``radius`` x 0.05 image widths find the highest horizon; the
    occlusion is the mean sine of the horizon elevations. A flat height gives 1.
    """
    if quality not in (4, 8, 16):
        raise DiffMatError(f"hbao.quality: unknown value {quality!r}; expected 4, 8 or 16")
    h = to_gray(input)
    if check_bool(use_world_units, "hbao.use_world_units"):
        depth = param4d(height_scale, h) / param4d(surface_size, h).clamp_min(1e-3)
    else:
        depth = param4d(height_depth, h) * HBAO_HEIGHT
    rad = param4d(radius, h).clamp_min(1e-4) * HBAO_RADIUS
    dirs = min(quality, 8)
    u, v = pixel_grid(h.shape[-1], h.device, h.dtype)
    occ: float | torch.Tensor = 0.0
    for d in range(dirs):
        a = 2 * math.pi * (d + 0.5) / dirs
        best = None
        for s in range(HBAO_STEPS):
            dist = rad * ((s + 1) / HBAO_STEPS)
            sample = sample_wrap(h, u + dist * math.cos(a), v + dist * math.sin(a))
            tan = (sample - h) * depth / dist
            best = tan if best is None else torch.maximum(best, tan)
        assert best is not None  # HBAO_STEPS >= 1
        occ = occ + (best / torch.sqrt(1 + best * best)).clamp_min(0.0)
    assert isinstance(occ, torch.Tensor)  # quality >= 4 directions
    return (1.0 - occ / dirs).clamp(0.0, 1.0)


AO_DEPTH_REFERENCE = 0.15      # the Height Depth at which ours is the reference's (its own default)
AO_BAND_BLURS = (2.2, 3.3)     # Blur HQ intensities that split the occlusion into three bands
AO_SCALES = (0.25, 0.5, 1.0)   # the three-blur model: fractions of the spreading radius
AO_MODELS = {0: "substance", 1: "three blurs"}


def ambient_occlusion(source: torch.Tensor, *, height_depth=0.15, spreading=0.15,
                      equalizer=(0.0, 0.0, 0.0), levels=(0.0, 0.5, 1.0), model: int = 0):
    """Ambient Occlusion (the older, blur-based node). ``model`` 0 draws it as the MATch
    reference does (``_reference_occlusion``), which is what Substance's node gives; 1 is the
    construction this engine had before (``_three_blur_occlusion``), which our shipped library
    graphs were authored and trained with and keep (docs/generators.md, stop 32)."""
    if model not in AO_MODELS:
        raise DiffMatError(f"ambient_occlusion_2.model: expected one of {sorted(AO_MODELS)}, got {model!r}")
    occlusion = _reference_occlusion if model == 0 else _three_blur_occlusion
    return occlusion(to_gray(source), param4d(height_depth, source), param4d(spreading, source),
                     param4d(equalizer, source), param4d(levels, source))


def _reference_occlusion(h, height_depth, spreading, equalizer, levels):
    """A texel is occluded by how far it sits below its neighbourhood: the Blur HQ (spreading x
    128) of the inverted height plus the height is 1 on a flat or convex surface and 1 − depth in
    a hollow of that depth, and Levels from 0.5 maps it to 1 − 2 x depth; it is squared on flat
    ground (times itself plus 1 − the blue of the height's normal map at intensity 16). The result
    is split into three bands by Blur HQ of 2.2 and 3.3; the equalizer (low, mid, high; 0 leaves a
    band as it is) raises the low band's mid point by half its value and scales the mid and high
    bands by 1 + 2 x its value; ``levels`` (in low, mid, high) is a final Levels.

    Our choices: the bands are split at full resolution (the reference halves the image for each,
    with blurs of the same size relative to the image); ``height_depth`` (which the reference
    lacks) scales the depth, ours equal to the reference's at Substance's default 0.15."""
    depth = height_depth / AO_DEPTH_REFERENCE
    rise = (1.0 - blur_hq(1.0 - h, intensity=spreading * 128.0) - h).clamp_min(0.0)
    ao = (1.0 - 2.0 * depth * rise).clamp(0.0, 1.0)
    flat = height_to_normal(h, intensity=16.0, input2alpha=False)[:, 2:3]
    ao = ao * (ao + 1.0 - flat).clamp_max(1.0)
    low_cut, mid_cut = AO_BAND_BLURS
    mid_band = blur_hq(ao, intensity=low_cut)
    low_band = blur_hq(mid_band, intensity=mid_cut)
    out = tone_levels(low_band, levelinmid=(equalizer[:, 0:1] + 1.0) * 0.5)
    out = out + (mid_band - low_band) * (1.0 + 2.0 * equalizer[:, 1:2])
    out = out + (ao - mid_band) * (1.0 + 2.0 * equalizer[:, 2:3])
    return tone_levels(out.clamp(0.0, 1.0), levelinlow=levels[:, 0:1], levelinmid=levels[:, 1:2],
                       levelinhigh=levels[:, 2:3])


def _three_blur_occlusion(h, height_depth, spreading, equalizer, levels):
    """Occlusion is how far the neighbourhood average (Gaussian, three scales up to spreading x
    0.25 image widths, weighted low / mid / high by 1 + 2 x the equalizer) rises above the height,
    times height_depth x 8; ``levels`` (low, mid, high) remaps the result, mid as a gamma inside
    the window. Flat height gives 1."""
    size = h.shape[-1]
    fx, fy = frequencies(size, h.device, h.dtype)
    f2 = fx * fx + fy * fy
    spread = spreading.clamp_min(1e-4) * 0.25
    weights = 1.0 + 2.0 * equalizer
    transfer: float | torch.Tensor = 0.0
    for k, frac in enumerate(AO_SCALES):
        sigma = spread * frac
        transfer = transfer + weights[:, k:k + 1] * (torch.exp(-2 * math.pi ** 2 * sigma ** 2 * f2) - 1.0)
    rise = torch.fft.irfft2(torch.fft.rfft2(h) * transfer, s=h.shape[-2:]) / len(AO_SCALES)
    ao = (1.0 - rise.clamp_min(0.0) * height_depth * 8.0).clamp(0.0, 1.0)
    lo, mid, hi = levels[:, 0:1], levels[:, 1:2], levels[:, 2:3]
    x = ((ao - lo) / (hi - lo).clamp_min(1e-3)).clamp(1e-6, 1.0)
    m = ((mid - lo) / (hi - lo).clamp_min(1e-3)).clamp(0.01, 0.99)
    gamma = math.log(0.5) / torch.log(m)
    return (x ** gamma).clamp(0.0, 1.0)


EDGE_GATE = (0.02, 0.05)  # steps this far above the tolerance start to draw a line, and draw a full one
# the step the tolerance 1 adds to the gate: the MATch reference draws a full line where the
# difference of the image and its 1-px blur passes (tolerance + 0.2) x 0.01 of 0.05, and that
# difference is about 0.31 of the step
EDGE_TOLERANCE_STEP = 0.05 * 0.01 / 0.31


def edge_detect(input: torch.Tensor, *, edge_width=2.0, edge_roundness=4.0, tolerance=0.0,
                invert: bool = False):
    """Edge Detect: lines along the contours of an image (black on white; white on black when
    ``invert``), as full a line for a small step across a contour as for a large one.

    Substance draws a line wherever the luminance steps at all (the MATch reference: the
    difference between the image and its 1-px blur through a Levels window that ``tolerance``,
    0 to 1, moves by steps of about 0.002 at most), so tiles or cells of random grey get lines as
    white as a black and white mask does. Here: the gradient magnitude
    (central differences) of the image blurred by sigma = ``edge_width`` / 2 (256-px pixels),
    normalised so that a step peaks at its height, is divided by its local peak (the largest
    value within two sigmas), which gives every contour the profile of a unit step; contours whose
    step is under ``tolerance`` x ``EDGE_TOLERANCE_STEP`` are gated out (``EDGE_GATE``: from a step
    0.02 above it, full at 0.05, clear of the blur's numerical noise); the profile is
    gained x 2 and rounded by a blur of ``edge_roundness`` / 2 pixels, then inverted, as the
    reference's graph ends with an inversion whatever its parameters."""
    x = to_gray(input)
    size = x.shape[-1]
    sigma = torch.sqrt((param4d(edge_width, x) * 0.5 * PX) ** 2 + (0.5 / size) ** 2)
    gu, gv = gradient_wrap(gaussian_blur(x, sigma))
    # a unit step blurred by sigma peaks at 1 / (sigma sqrt(2 pi)); central differences widen it
    e = torch.sqrt(gu * gu + gv * gv + 1e-12) * torch.sqrt(sigma ** 2 + (1.0 / size) ** 2) * math.sqrt(2 * math.pi)
    # the largest value within two sigmas, wrapping: a square max is a row max of a column max
    reach = 2 * math.ceil(2 * float(sigma.detach().max()) * size) + 1
    half = reach // 2
    peak = torch.nn.functional.max_pool2d(torch.nn.functional.pad(e, (half, half, 0, 0), mode="circular"),
                                          (1, reach), stride=1)
    peak = torch.nn.functional.max_pool2d(torch.nn.functional.pad(peak, (0, 0, half, half), mode="circular"),
                                          (reach, 1), stride=1)
    tol = param4d(tolerance, x) * EDGE_TOLERANCE_STEP
    gate = ((peak - tol - EDGE_GATE[0]) / (EDGE_GATE[1] - EDGE_GATE[0])).clamp(0.0, 1.0)
    out = (e / (peak + 1e-6) * gate * 2.0).clamp(0.0, 1.0)
    out = gaussian_blur(out, param4d(edge_roundness, x).abs() * 0.5 * PX).clamp(0.0, 1.0)
    return out if check_bool(invert, "edge_detect.invert") else 1.0 - out


BEVEL_REACH = 128.0        # 256-px pixels of bevel at distance 1 (the MATch reference)


def bevel(input: torch.Tensor, *, distance=0.5, smoothing=0.0, normal_intensity=10.0, normal_format: int = 0):
    """Bevel: a linear ramp around the shapes of a mask (its pixels above 0.5), as the public MATch
    reference builds it from Substance's Distance node: a positive ``distance`` grows the shapes
    outwards (1 on the mask, falling to 0 at ``distance`` x ``BEVEL_REACH`` pixels of a 256-px
    image outside it), a negative one bevels them inwards (0 at the contour, rising to 1 that far
    inside), 0 returns the input. The mask is thresholded, so no gradient reaches the input (as in
    the Distance node); the height is differentiable in ``distance``. ``smoothing`` blurs the height
    (x 2 pixels of 256). Returns (height, normal), the normal computed from the height with
    ``normal_intensity``. Thin shapes keep their bevel: a line one pixel wide bevelled outwards is
    a ridge as wide as the bevel."""
    _check_format(normal_format, "bevel")
    x = to_gray(input)
    d = param4d(distance, x)
    reach = d.abs() * BEVEL_REACH
    h = x
    if bool((d > 0).any()):   # each distance transform only when some batch item needs it
        h = torch.where(d > 0, distance_fade(x, distance=reach), h)
    if bool((d < 0).any()):
        h = torch.where(d < 0, 1.0 - distance_fade(1.0 - x, distance=reach), h)
    h = gaussian_blur(h, param4d(smoothing, x).abs() * 2.0 * PX).clamp(0.0, 1.0)
    return h, height_to_normal_map(h, normal_intensity, normal_format)


def metallic_roughness_to_specular_glossiness(basecolor: torch.Tensor, metallic: torch.Tensor,
                                              roughness: torch.Tensor):
    """BaseColor/Metallic/Roughness to Diffuse/Specular/Glossiness (sRGB colours):
    diffuse = base x (1 - metallic), specular = lerp(0.04, base, metallic) in linear space,
    glossiness = 1 - roughness."""
    base = basecolor if basecolor.shape[1] == COLOR else torch.cat([basecolor] * 3 + [torch.ones_like(basecolor)], 1)
    m = to_gray(metallic)
    lin = srgb_to_linear(base)[:, :3]
    diffuse_lin = lin * (1.0 - m)
    spec_lin = 0.04 + (lin - 0.04) * m
    alpha = base[:, 3:]

    def pack(rgb):
        rgb = linear_to_srgb(rgb)
        return torch.cat([rgb, alpha.expand(rgb.shape[0], -1, -1, -1)], dim=1)

    return pack(diffuse_lin), pack(spec_lin), (1.0 - to_gray(roughness)).clamp(0.0, 1.0)
