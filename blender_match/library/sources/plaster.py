"""Plaster: a hand-troweled, painted stucco wall (beige by default).

Structure
- Height: dense small stucco bumps (black-and-white spots through a histogram scan, softened)
  smeared along long trowel strokes (a slope blur driven by a swirling liquid noise), with their
  tops knocked flat by the trowel, a low trowel ridge relief and a fine sand grain.
- Base colour: the exposed paint colour, lighter on the bump tops and darker in the hollows, with a
  soft large-scale mottling (uneven paint / plaster absorption).
- Roughness: matte paint; the trowel-flattened tops are a little smoother than the hollows.
- Normal: from the height (OpenGL) combined with a fine grain detail normal. Metallic 0.

Exposed parameters
- ``color`` (float3, sRGB): the paint colour.
- ``bump_scale``: how many stucco bumps per tile.
- ``bumps``: how much of the wall the bumps cover (0 smooth plaster, 1 heavy stucco).
- ``trowel``: strength of the trowel strokes (smear length, flattening, ridges).
- ``roughness``: the mean roughness.
- ``relief``: the strength of the normal map.
"""
from __future__ import annotations

from blender_match.library.authoring import OUR_OCCLUSION, constant_map
from blender_match.library.expressions import clamp, get, lerp, vector
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("plaster")
    g.expose("color", [0.60, 0.51, 0.38], min=0.0, max=1.0)
    g.expose("bump_scale", 1.0, min=0.5, max=2.0)
    g.expose("bumps", 0.55, min=0.0, max=1.0)
    g.expose("trowel", 0.5, min=0.0, max=1.0)
    g.expose("roughness", 0.78, min=0.4, max=1.0)
    g.expose("relief", 0.5, min=0.0, max=1.0)
    bump_scale = get("bump_scale")
    trowel = get("trowel")

    # ---- generators -------------------------------------------------------------------------
    g.add("spots", "perlin_noise", seed=21, scale=40.0)
    g.bind("spots", "scale", clamp(bump_scale * 40.0, 1.0, 256.0).graph())
    g.add("swirl", "liquid", seed=22, scale=2.0, disorder=0.2)
    g.add("mottle", "clouds_2", seed=23, scale=3.0)
    g.add("grain", "gaussian_noise", seed=24, scale=3.0)

    # ---- stucco bumps -----------------------------------------------------------------------------
    g.add("bumps_mask", "histogram_scan", {"input_1": "spots"}, position=0.5, contrast=0.25)
    g.bind("bumps_mask", "position", lerp(0.25, 0.75, get("bumps")).graph())
    g.add("bumps_soft", "blur_hq_grayscale", {"source": "bumps_mask"}, intensity=0.8)
    g.add("bumps_smear", "slope_blur_grayscale", {"source": "bumps_soft", "effect": "swirl"},
          samples=4, mode=1, intensity=1.8)
    g.bind("bumps_smear", "intensity", lerp(0.2, 3.5, trowel).graph())
    # the trowel knocks the bump tops flat: compress the top of the range
    g.add("bumps_flat", "histogram_range", {"input": "bumps_smear"}, range=0.8, position=0.4)
    g.add("bumps_top", "blend", {"source": "bumps_flat", "destination": "bumps_smear"}, blendingmode=6,
          opacitymult=0.6)
    g.bind("bumps_top", "opacitymult", lerp(0.0, 0.9, trowel).graph())

    # ---- trowel ridges and grain ------------------------------------------------------------------
    g.add("ridges", "histogram_range", {"input": "swirl"}, range=0.6, position=0.5)
    g.add("h_ridges", "blend", {"source": "ridges", "destination": "bumps_top"}, blendingmode=4, opacitymult=0.15)
    g.bind("h_ridges", "opacitymult", lerp(0.0, 0.3, trowel).graph())
    g.add("h_grain", "blend", {"source": "grain", "destination": "h_ridges"}, blendingmode=4, opacitymult=0.08)
    g.add("height", "histogram_range", {"input": "h_grain"}, range=0.8, position=0.5)
    g.set_output("height", "height")

    # ---- normal ---------------------------------------------------------------------------------
    g.add("n_main", "normal", {"input1": "height"}, intensity=5.0, inversedy=True, input2alpha=False)
    g.bind("n_main", "intensity", lerp(0.5, 12.0, get("relief")).graph())
    g.add("n_grain", "normal", {"input1": "grain"}, intensity=0.6, inversedy=True, input2alpha=False)
    g.add("n_out", "normal_combine", {"input": "n_main", "input_1": "n_grain"})
    g.set_output("normal", "n_out")

    # ---- base colour ----------------------------------------------------------------------------
    g.add("shade_src", "blend", {"source": "mottle", "destination": "height"}, blendingmode=4, opacitymult=0.14)
    g.add("variation", "gradient", {"input1": "shade_src"},
          positions=[0.0, 0.45, 1.0],
          colors=[0.74, 0.72, 0.70, 1.0, 0.91, 0.90, 0.89, 1.0, 1.0, 1.0, 0.99, 1.0])
    g.add("tint", "uniform", outputcolor=[0.60, 0.51, 0.38, 1.0])
    g.bind("tint", "outputcolor", vector(get("color", 3), 1.0).graph())
    g.add("col_out", "blend", {"source": "variation", "destination": "tint"}, blendingmode=3)
    g.set_output("basecolor", "col_out")

    # ---- roughness ------------------------------------------------------------------------------
    g.add("r_src", "invert_grayscale", {"source": "bumps_top"})
    g.add("r_base", "histogram_range", {"input": "r_src"}, range=0.12, position=0.78)
    g.bind("r_base", "position", get("roughness").graph())
    g.add("r_out", "blend", {"source": "grain", "destination": "r_base"}, blendingmode=4, opacitymult=0.05)
    g.set_output("roughness", "r_out")

    # ---- metallic, AO ---------------------------------------------------------------------------
    constant_map(g, "metal", 0.0)
    g.set_output("metallic", "metal")
    g.add("ao", "ambient_occlusion_2", {"source": "height"}, height_depth=0.1, spreading=0.08,
          model=OUR_OCCLUSION)
    g.set_output("ambientocclusion", "ao:ambient_occlusion")
    return g


FAMILY = "plaster"

SAMPLE_RANGES = {
    "exposed.color": ([0.36, 0.33, 0.28], [0.92, 0.90, 0.87]),
    "exposed.bump_scale": (0.6, 1.8),
    "exposed.bumps": (0.15, 0.95),
    "exposed.trowel": (0.0, 1.0),
    "exposed.roughness": (0.55, 0.95),
    "exposed.relief": (0.2, 0.9),
    "shade_src.opacitymult": (0.1, 0.5),
    "variation.colors": ([0.68, 0.67, 0.66, 1.0, 0.88, 0.87, 0.86, 1.0, 0.98, 0.98, 0.97, 1.0],
                         [0.8, 0.78, 0.76, 1.0, 0.94, 0.93, 0.92, 1.0, 1.0, 1.0, 1.0, 1.0]),
    "bumps_soft.intensity": (0.4, 3.0),
    "h_grain.opacitymult": (0.02, 0.16),
}
