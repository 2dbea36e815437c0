"""Marble: a polished white marble slab with grey veins (Carrara-like).

Structure
- Veins: iso-lines of a soft cloud noise, warped by a fractal noise (turbulence), picked out by a
  narrow histogram select: a main network of bold veins and a second, finer network from another
  warped noise; each gets a soft halo (blur) so the veins bleed into the stone.
- Base colour: the exposed stone colour with a faint cloudy variation, tinted towards the exposed
  vein colour along the veins and their halos.
- Roughness: low (polished), slightly higher in the veins (softer minerals polish less well).
- Height: almost flat: the veins are very slightly recessed; a faint long-wave polish ripple.
- Normal: from the height (OpenGL), weak. Metallic 0.

Exposed parameters
- ``color`` (float3, sRGB): the stone colour.
- ``vein_color`` (float3, sRGB): the colour of the veins.
- ``veins``: vein width / amount.
- ``turbulence``: how tortuous the veins are (warp strength).
- ``scale``: how many vein structures per tile.
- ``roughness``: the polish (mean roughness).
"""
from __future__ import annotations

from blender_match.library.authoring import constant_map
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("marble")
    g.expose("color", [0.88, 0.87, 0.85], min=0.0, max=1.0)
    g.expose("vein_color", [0.36, 0.37, 0.40], min=0.0, max=1.0)
    g.expose("veins", 0.5, min=0.0, max=1.0)
    g.expose("turbulence", 0.5, min=0.0, max=1.0)
    g.expose("scale", 1.0, min=0.5, max=2.0)
    g.expose("roughness", 0.12, min=0.02, max=0.5)
    scale = get("scale")
    veins = get("veins")
    turbulence = get("turbulence")

    # ---- generators -------------------------------------------------------------------------
    g.add("base_noise", "clouds_2", seed=31, scale=2.0)
    g.bind("base_noise", "scale", (scale * 2.0).graph())
    g.add("fine_noise", "clouds_3", seed=32, scale=4.0)
    g.bind("fine_noise", "scale", (scale * 4.0).graph())
    g.add("turb", "fractal_sum_1", seed=33, scale=3.0, roughness=0.6)
    g.add("cloudy", "clouds_1", seed=34, scale=3.0)
    g.add("turb_smooth", "blur_hq_grayscale", {"source": "turb"}, intensity=5.0)

    # ---- main veins ---------------------------------------------------------------------------------
    g.add("base_smooth", "blur_hq_grayscale", {"source": "base_noise"}, intensity=7.0)
    g.add("base_contrast", "contrast_luminosity_grayscale", {"input": "base_smooth"}, contrast=0.55)
    g.add("warped", "warp", {"input1": "base_contrast", "inputgradient": "turb_smooth"}, intensity=0.35)
    g.bind("warped", "intensity", lerp(0.05, 0.7, turbulence).graph())
    g.add("vein_main", "histogram_select", {"input": "warped"}, position=0.5, range=0.012, contrast=0.75)
    g.bind("vein_main", "range", lerp(0.003, 0.025, veins).graph())
    g.add("vein_halo", "blur_hq_grayscale", {"source": "vein_main"}, intensity=2.5)

    # ---- secondary fine veins ---------------------------------------------------------------------
    g.add("fine_smooth", "blur_hq_grayscale", {"source": "fine_noise"}, intensity=4.0)
    g.add("fine_contrast", "contrast_luminosity_grayscale", {"input": "fine_smooth"}, contrast=0.5)
    g.add("warped_fine", "warp", {"input1": "fine_contrast", "inputgradient": "turb_smooth"}, intensity=0.25)
    g.bind("warped_fine", "intensity", lerp(0.03, 0.5, turbulence).graph())
    g.add("vein_fine", "histogram_select", {"input": "warped_fine"}, position=0.45, range=0.004, contrast=0.8)
    g.bind("vein_fine", "range", lerp(0.001, 0.008, veins).graph())
    g.add("vein_fine_mask", "blend", {"source": "cloudy", "destination": "vein_fine"}, blendingmode=3,
          opacitymult=0.8)

    # ---- vein mask: main veins, their halo and fine veins ----------------------------------------------
    g.add("v_halo", "blend", {"source": "vein_halo", "destination": "vein_main"}, blendingmode=5, opacitymult=0.55)
    g.add("v_all", "blend", {"source": "vein_fine_mask", "destination": "v_halo"}, blendingmode=5, opacitymult=0.7)

    # ---- base colour ----------------------------------------------------------------------------
    g.add("stone_var", "gradient", {"input1": "cloudy"},
          positions=[0.0, 1.0], colors=[0.95, 0.95, 0.96, 1.0, 1.0, 0.995, 0.985, 1.0])
    g.add("tint", "uniform", outputcolor=[0.88, 0.87, 0.85, 1.0])
    g.bind("tint", "outputcolor", vector(get("color", 3), 1.0).graph())
    g.add("stone", "blend", {"source": "stone_var", "destination": "tint"}, blendingmode=3)
    g.add("vein_tint", "uniform", outputcolor=[0.36, 0.37, 0.40, 1.0])
    g.bind("vein_tint", "outputcolor", vector(get("vein_color", 3), 1.0).graph())
    g.add("col_out", "blend", {"source": "vein_tint", "destination": "stone", "opacity": "v_all"},
          blendingmode=0, opacitymult=0.9)
    g.set_output("basecolor", "col_out")

    # ---- height -----------------------------------------------------------------------------------
    g.add("ripple", "histogram_range", {"input": "cloudy"}, range=0.06, position=0.6)
    g.add("h_out", "blend", {"source": "vein_main", "destination": "ripple"}, blendingmode=2, opacitymult=0.05)
    g.set_output("height", "h_out")

    # ---- normal -----------------------------------------------------------------------------------
    g.add("n_out", "normal", {"input1": "h_out"}, intensity=3.0, inversedy=True, input2alpha=False)
    g.set_output("normal", "n_out")

    # ---- roughness --------------------------------------------------------------------------------
    g.add("r_base", "histogram_range", {"input": "cloudy"}, range=0.03, position=0.12)
    g.bind("r_base", "position", get("roughness").graph())
    g.add("r_out", "blend", {"source": "v_all", "destination": "r_base"}, blendingmode=1, opacitymult=0.12)
    g.set_output("roughness", "r_out")

    # ---- metallic -----------------------------------------------------------------------------------
    constant_map(g, "metal", 0.0)
    g.set_output("metallic", "metal")
    return g


FAMILY = "stone"

SAMPLE_RANGES = {
    "exposed.color": ([0.72, 0.70, 0.66], [0.96, 0.95, 0.94]),
    "exposed.vein_color": ([0.12, 0.12, 0.12], [0.6, 0.58, 0.56]),
    "exposed.veins": (0.15, 0.9),
    "exposed.turbulence": (0.1, 0.9),
    "exposed.scale": (0.6, 1.8),
    "exposed.roughness": (0.05, 0.3),
    "v_halo.opacitymult": (0.2, 0.8),
    "v_all.opacitymult": (0.3, 1.0),
    "vein_halo.intensity": (1.0, 5.0),
    "col_out.opacitymult": (0.6, 1.0),
    "vein_main.position": (0.35, 0.65),
    "vein_fine.position": (0.3, 0.6),
}
