"""Differentiable flash rendering of material maps (the MATch paper, section 4.1, eq. 2).

The BRDF is the simplified Disney/metallic-roughness model: Lambertian diffuse plus a GGX
microfacet specular lobe with Smith shadowing (Schlick-GGX form) and Schlick's Fresnel; metallic
blends a dielectric (F0 = 0.04, diffuse = base colour) and a metal (F0 = base colour, no diffuse).
A point light sits at a pinhole camera above the sample's centre (a phone with its flash): for
every pixel the light and view directions coincide. For evaluation under a "novel light",
``light_offset`` moves the light away from the camera (the general half-vector form is used then).

Maps follow Blender's conventions: base colour sRGB-encoded, normal in OpenGL convention encoded in
[0, 1], roughness perceptual (alpha = roughness squared), metallic in [0, 1]. The output is an sRGB
image clamped to [0, 1].

Brushed metals add an anisotropy level and angle (``vocabulary.ANISOTROPY``, ``ANISOTROPY_ANGLE``):
the GGX lobe of Burley 2012 as Blender's Principled BSDF sets it up (Cycles' ``svm/closure.h``):
alpha/aspect across the brushing and alpha*aspect along it, aspect = sqrt(1 - 0.9 level), the
brushing direction being +u turned by the angle about the shading normal (which, after Cycles'
projection of its tangent onto the plane of that normal, is +u projected onto it and turned there).
The Smith term keeps its Schlick-GGX form with the roughness projected on each direction's azimuth.
Both are written as the isotropic formula plus terms that are exactly zero at level 0, so a level-0
map renders the isotropic lobe to the bit, and without the maps none of it is computed.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import torch

from ..colour import LINEAR_KNEE, SRGB_GAMMA, SRGB_KNEE, SRGB_OFFSET, SRGB_SCALE, SRGB_SLOPE
from ..vocabulary import ANISOTROPY, ANISOTROPY_ANGLE
from .errors import DiffMatError
from .functional.common import param4d

EPS = 1e-6


@dataclass(frozen=True)
class FlashCamera:
    """A phone held above the sample, flash beside the lens.

    ``fov`` is the camera's full field of view in degrees (the sample fills the frame),
    ``distance`` is in sample widths, ``power`` scales the flash so that a white Lambertian sample
    at the centre renders at ``power`` in linear radiance (1 would just saturate).

    ``falloff`` is what a real phone adds to that ideal flash: its beam pattern and its lens's
    vignetting, as a smooth factor on the light over the frame, exp(a u + b v + c u² + d v² + e uv)
    with (u, v) from -1 to 1 across the frame (u right, v up). All zero (the default): the ideal
    flash. ``diffmat.calibration.solve_lighting`` finds it for a photo.
    """

    fov: float = 50.0
    distance: float | None = None
    power: float = 0.75
    falloff: tuple[float, ...] = (0.0, 0.0, 0.0, 0.0, 0.0)

    def camera_distance(self) -> float:
        if self.distance is not None:
            return self.distance
        return 0.5 / math.tan(math.radians(self.fov) / 2)

    def falloff_field(self, x: torch.Tensor, y: torch.Tensor) -> torch.Tensor | None:
        """The ``falloff`` factor at the sample-plane positions ``x``, ``y`` of the frame's pixels
        (sample widths from the centre, y up), scaled to a mean of one over them (it moves light
        about the frame; the level is the gain's), or None when there is none."""
        if not any(self.falloff):
            return None
        a, b, c, d, e = self.falloff
        u, v = 2 * x, 2 * y
        field = torch.exp(a * u + b * v + c * u * u + d * v * v + e * u * v)
        return field / field.mean()


def srgb_to_linear(x: torch.Tensor) -> torch.Tensor:
    """sRGB-encoded values, clamped to [0, 1], to linear (the curve of ``blender_match.colour``)."""
    x = x.clamp(0.0, 1.0)
    curve = ((x + SRGB_OFFSET) / SRGB_SCALE).clamp_min(EPS) ** SRGB_GAMMA
    return torch.where(x <= SRGB_KNEE, x / SRGB_SLOPE, curve)


def linear_to_srgb(x: torch.Tensor) -> torch.Tensor:
    """Linear values, clamped to [0, 1], to sRGB-encoded (the curve of ``blender_match.colour``)."""
    x = x.clamp(0.0, 1.0)
    curve = SRGB_SCALE * x.clamp_min(1e-8) ** (1 / SRGB_GAMMA) - SRGB_OFFSET
    return torch.where(x <= LINEAR_KNEE, x * SRGB_SLOPE, curve)


def _rgb(x: torch.Tensor) -> torch.Tensor:
    return x[:, :3] if x.shape[1] >= 3 else x.expand(-1, 3, -1, -1)


def _gray(x: torch.Tensor) -> torch.Tensor:
    return x[:, :1] if x.shape[1] == 1 else x[:, :3].mean(dim=1, keepdim=True)


def render_flash(basecolor: torch.Tensor, normal: torch.Tensor | None = None,
                 roughness: torch.Tensor | None = None, metallic: torch.Tensor | None = None,
                 camera: FlashCamera = FlashCamera(),
                 light_offset: tuple[float, float] | None = None,
                 anisotropy: torch.Tensor | None = None, anisotropy_angle: torch.Tensor | None = None) -> torch.Tensor:
    """Render maps (N, C, H, W) under a co-located flash; returns an sRGB (N, 3, H, W) image.

    Missing maps default to a flat normal, roughness 0.5 and metallic 0; without ``anisotropy`` the
    lobe is isotropic (``anisotropy_angle`` alone changes nothing), an angle missing beside it is 0
    (brushed along +u). Differentiable in every map.
    ``light_offset`` (dx, dy), in sample widths (x right, y up), moves the light away from the
    camera in the plane parallel to the sample (a "novel light" view, for evaluation, which has no
    ``camera.falloff``: that belongs to the phone's flash); None keeps the co-located flash.
    """
    n_img, _, h, w = basecolor.shape
    like = basecolor
    albedo = srgb_to_linear(_rgb(basecolor))
    if normal is None:
        nrm = torch.zeros(1, 3, h, w, dtype=like.dtype, device=like.device)
        nrm[:, 2] = 1.0
    else:
        nrm = _rgb(normal) * 2 - 1
        nrm = nrm / nrm.norm(dim=1, keepdim=True).clamp_min(EPS)
    rough = _gray(roughness) if roughness is not None else torch.full_like(albedo[:, :1], 0.5)
    metal = _gray(metallic) if metallic is not None else torch.zeros_like(albedo[:, :1])

    # positions on the sample plane (width 1, centred) and the direction to the camera/light
    d = camera.camera_distance()
    ys = (torch.arange(h, dtype=like.dtype, device=like.device) + 0.5) / h - 0.5
    xs = (torch.arange(w, dtype=like.dtype, device=like.device) + 0.5) / w - 0.5
    y, x = torch.meshgrid(-ys, xs, indexing="ij")
    brushing = None if anisotropy is None else _Brushing(nrm, _gray(anisotropy), anisotropy_angle)
    if light_offset is not None:
        return _render_offset_light(albedo, nrm, rough, metal, camera, x, y, light_offset, brushing)
    to_light = torch.stack([-x, -y, torch.full_like(x, d)])[None]
    dist2 = (to_light ** 2).sum(dim=1, keepdim=True)
    wi = to_light / dist2.sqrt()

    cos = (nrm * wi).sum(dim=1, keepdim=True).clamp_min(EPS)  # n.l = n.v = n.h (co-located)
    irradiance = param4d(camera.power * math.pi * d * d, like) / dist2 * cos
    field = camera.falloff_field(x, y)
    if field is not None:
        irradiance = irradiance * field
    lobe = None if brushing is None else brushing.colocated(wi)
    return linear_to_srgb(_brdf(albedo, rough, metal, cos, cos, cos, lobe=lobe) * irradiance)


class _Brushing:
    """The anisotropic lobe's frame at every pixel: ``along`` the brushing and ``across`` it (unit
    vectors in the plane perpendicular to the shading normal) and the lobe's stretches,
    ``smooth`` = aspect² - 1 (<= 0, the smoother direction, along) and ``rough`` = 1/aspect² - 1
    (>= 0, across); both are exactly zero at level 0."""

    def __init__(self, nrm: torch.Tensor, level: torch.Tensor, angle: torch.Tensor | None):
        theta = 2 * math.pi * (_gray(angle) if angle is not None else torch.zeros_like(level))
        nx, ny, nz = nrm[:, :1], nrm[:, 1:2], nrm[:, 2:3]
        # +u projected onto the normal's plane, and n x u, which is perpendicular to it in that
        # plane and of the same length: the projected +u turned by theta about the normal
        projected = torch.cat([1 - nx * nx, -nx * ny, -nx * nz], dim=1)
        turned = torch.cat([torch.zeros_like(nx), nz, -ny], dim=1)
        along = torch.cos(theta) * projected + torch.sin(theta) * turned
        self.along = along / along.norm(dim=1, keepdim=True).clamp_min(EPS)
        self.across = torch.linalg.cross(nrm.expand_as(self.along), self.along, dim=1)
        aspect2 = 1 - 0.9 * level.clamp(0.0, 1.0)
        self.smooth = aspect2 - 1
        self.rough = 1 / aspect2 - 1

    def colocated(self, w: torch.Tensor) -> _Lobe:
        """The lobe's terms when the light, the view and the half vector are the one direction
        ``w`` (unit, (N, 3, H, W)): the co-located flash, one Smith factor for both."""
        across, along = self._squares(w)
        smith = self._smith(across, along)
        return _Lobe(self._ndf(across, along), smith, smith)

    def lobe(self, half: torch.Tensor, wi: torch.Tensor, wo: torch.Tensor) -> _Lobe:
        """The lobe's terms for the half vector, the light and the view directions (unit)."""
        return _Lobe(self._ndf(*self._squares(half)), self._smith(*self._squares(wi)), self._smith(*self._squares(wo)))

    def _squares(self, w: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        """(w . across)² and (w . along)²."""
        return (w * self.across).sum(dim=1, keepdim=True) ** 2, (w * self.along).sum(dim=1, keepdim=True) ** 2

    def _ndf(self, across: torch.Tensor, along: torch.Tensor) -> torch.Tensor:
        """alpha² times the anisotropic GGX denominator's inner sum, minus the isotropic one's
        (n.h² (alpha² - 1) + 1): h_across² (aspect² - 1) + h_along² (1/aspect² - 1)."""
        return across * self.smooth + along * self.rough

    def _smith(self, across: torch.Tensor, along: torch.Tensor) -> torch.Tensor:
        """alpha projected on a direction's azimuth over alpha, sqrt((across²/aspect² + along²
        aspect²) / (across² + along²)), written as sqrt(1 + a term zero at level 0)."""
        return torch.sqrt(1 + (across * self.rough + along * self.smooth) / (across + along).clamp_min(EPS))


@dataclass(frozen=True)
class _Lobe:
    """What anisotropy adds to ``_brdf``: ``ndf``, the term added to the GGX denominator's
    n.h² (alpha² - 1) + 1, and the factors on the Smith k of the light and the view."""

    ndf: torch.Tensor
    smith_l: torch.Tensor
    smith_v: torch.Tensor


def _brdf(albedo, rough, metal, n_l, n_v, n_h, v_h=None, lobe: _Lobe | None = None) -> torch.Tensor:
    """Diffuse + GGX specular (Smith shadowing in the Schlick-GGX form, Schlick's Fresnel) from
    the clamped cosines. ``v_h`` None is the co-located case: v.h = 1, so the Fresnel term is F0
    and the two Smith terms are one. ``lobe``: the anisotropic lobe's terms (None: isotropic)."""
    alpha = (rough.clamp(0.02, 1.0)) ** 2
    a2 = alpha ** 2
    spread = (n_h ** 2) * (a2 - 1) + 1
    ggx = a2 / (math.pi * (spread if lobe is None else spread + lobe.ndf) ** 2)
    k = alpha / 2
    k_l, k_v = (k, k) if lobe is None else (k * lobe.smith_l, k * lobe.smith_v)
    g_l = n_l / (n_l * (1 - k_l) + k_l)
    g_v = g_l if n_v is n_l else n_v / (n_v * (1 - k_v) + k_v)
    f0 = 0.04 * (1 - metal) + albedo * metal
    fresnel = f0 if v_h is None else f0 + (1 - f0) * (1 - v_h) ** 5
    specular = ggx * fresnel * g_l * g_v / (4 * n_l * n_v)
    diffuse = albedo * (1 - metal) / math.pi
    return diffuse + specular


def _render_offset_light(albedo, nrm, rough, metal, camera: FlashCamera, x, y, light_offset,
                         brushing: _Brushing | None) -> torch.Tensor:
    """The same BRDF with the light at ``light_offset`` from the camera: the light and view
    directions differ, so the half vector, both Smith terms and Schlick's Fresnel at v.h are
    evaluated in full. With a zero offset it equals the co-located formula."""
    dx, dy = (float(v) for v in light_offset)
    d = camera.camera_distance()
    to_view = torch.stack([-x, -y, torch.full_like(x, d)])[None]
    to_light = torch.stack([dx - x, dy - y, torch.full_like(x, d)])[None]
    dist2 = (to_light ** 2).sum(dim=1, keepdim=True)
    wi = to_light / dist2.sqrt()
    wo = to_view / to_view.norm(dim=1, keepdim=True)
    half = wi + wo
    half = half / half.norm(dim=1, keepdim=True).clamp_min(EPS)
    n_l = (nrm * wi).sum(dim=1, keepdim=True).clamp_min(EPS)
    n_v = (nrm * wo).sum(dim=1, keepdim=True).clamp_min(EPS)
    n_h = (nrm * half).sum(dim=1, keepdim=True).clamp_min(EPS)
    v_h = (wo * half).sum(dim=1, keepdim=True).clamp(0.0, 1.0)
    irradiance = param4d(camera.power * math.pi * d * d, albedo) / dist2 * n_l
    lobe = None if brushing is None else brushing.lobe(half, wi, wo)
    return linear_to_srgb(_brdf(albedo, rough, metal, n_l, n_v, n_h, v_h, lobe) * irradiance)


def render_maps(maps: dict[str, torch.Tensor], camera: FlashCamera = FlashCamera(),
                light_offset: tuple[float, float] | None = None) -> torch.Tensor:
    """``render_flash`` from a MaterialGraph's output dictionary (``light_offset``: see there)."""
    if "basecolor" not in maps:
        raise DiffMatError("render_maps: the maps have no basecolor")
    return render_flash(maps["basecolor"], maps.get("normal"), maps.get("roughness"), maps.get("metallic"), camera,
                        light_offset, maps.get(ANISOTROPY), maps.get(ANISOTROPY_ANGLE))
