"""Concrete: a cast, slightly weathered grey concrete slab.

Structure
- Height: a large, soft undulation (clouds) plus a mid-frequency cement texture (fractal sum) and a
  fine sand grain (gaussian noise); air-bubble pores (gaussian spots pushed through a histogram
  scan) and a sparse network of hairline cracks (warped cell borders, masked by a grunge map so
  only some of them show) are carved into it.
- Base colour: the exposed tint times a soft luminance variation (a three-key gradient of the tone
  map), with water / dirt stains (a second grunge map) and darker pores and cracks.
- Roughness: high and nearly uniform (bare cement), rougher in the pores and cracks, slightly
  smoother in the stains.
- Normal: the height through a Normal node (OpenGL), combined with a fine grain detail normal.
- Metallic 0; ambient occlusion from the height.

Exposed parameters
- ``color`` (float3, sRGB): the overall cement colour (tint; the shading multiplies it).
- ``scale``: how many cement features per tile (drives every generator's scale).
- ``wear``: age: amount of stains and cracks.
- ``pores``: density and size of the air-bubble pores.
- ``roughness``: the mean roughness.
- ``relief``: the strength of the normal map.
"""
from __future__ import annotations

from blender_match.library.authoring import OUR_OCCLUSION, color_over, constant_map
from blender_match.library.expressions import clamp, get, lerp, vector
from blender_match.translator.runtime import SbsGraph

WHITE = [1.0, 1.0, 1.0, 1.0]


def build() -> SbsGraph:
    g = SbsGraph("concrete")
    g.expose("color", [0.50, 0.49, 0.47], min=0.0, max=1.0)
    g.expose("scale", 1.0, min=0.5, max=2.0)
    g.expose("wear", 0.35, min=0.0, max=1.0)
    g.expose("pores", 0.5, min=0.0, max=1.0)
    g.expose("roughness", 0.86, min=0.5, max=1.0)
    g.expose("relief", 0.5, min=0.0, max=1.0)
    scale = get("scale")

    # ---- generators -------------------------------------------------------------------------
    g.add("big", "clouds_2", seed=11, scale=2.0)
    g.bind("big", "scale", (scale * 2.0).graph())
    g.add("mid", "fractal_sum_1", seed=12, scale=6.0, roughness=0.55)
    g.bind("mid", "scale", (scale * 6.0).graph())
    g.add("grain", "gaussian_noise", seed=13, scale=2.0)
    g.add("spots", "gaussian_spots_1", seed=14, scale=6.0)
    g.bind("spots", "scale", clamp(scale * 6.0, 1.0, 32.0).graph())
    g.add("cells", "cells_3", seed=15, scale=5, width=0.07, disorder=0.4)
    g.add("stain_src", "grunge_map_008", seed=17, scale=2.0, contrast=0.6, balance=0.5)

    # ---- tone (large + mid + grain) ------------------------------------------------------------
    g.add("tone", "blend", {"source": "mid", "destination": "big"}, blendingmode=0, opacitymult=0.45)
    g.add("tone_grain", "blend", {"source": "grain", "destination": "tone"}, blendingmode=4, opacitymult=0.18)

    # ---- pores ----------------------------------------------------------------------------------
    g.add("pores", "histogram_scan", {"input_1": "spots"}, position=0.07, contrast=0.85)
    g.bind("pores", "position", lerp(0.015, 0.14, get("pores")).graph())
    g.add("pores_soft", "blur", {"input1": "pores"}, intensity=0.6)

    # ---- cracks ---------------------------------------------------------------------------------
    g.add("cells_warped", "warp", {"input1": "cells", "inputgradient": "mid"}, intensity=0.25)
    g.add("crack_lines", "histogram_scan", {"input_1": "cells_warped"}, position=0.8, contrast=0.6)
    g.add("crack_lines_inv", "invert_grayscale", {"source": "crack_lines"})
    g.add("crack_mask", "histogram_scan", {"input_1": "big"}, position=0.3, contrast=0.4)
    g.bind("crack_mask", "position", lerp(0.0, 0.6, get("wear")).graph())
    g.add("cracks", "blend", {"source": "crack_mask", "destination": "crack_lines_inv"}, blendingmode=3)

    # ---- stains ---------------------------------------------------------------------------------
    g.add("stains", "histogram_scan", {"input_1": "stain_src"}, position=0.35, contrast=0.0)
    g.bind("stains", "position", lerp(0.05, 0.75, get("wear")).graph())

    # ---- height ---------------------------------------------------------------------------------
    g.add("h_base", "histogram_range", {"input": "tone_grain"}, range=0.5, position=0.6)
    g.add("h_pores", "blend", {"source": "pores_soft", "destination": "h_base"}, blendingmode=2, opacitymult=0.45)
    g.add("h_cracks", "blend", {"source": "cracks", "destination": "h_pores"}, blendingmode=2, opacitymult=0.35)
    g.set_output("height", "h_cracks")

    # ---- normal ---------------------------------------------------------------------------------
    g.add("n_main", "normal", {"input1": "h_cracks"}, intensity=6.0, inversedy=True, input2alpha=False)
    g.bind("n_main", "intensity", lerp(0.5, 14.0, get("relief")).graph())
    g.add("n_grain", "normal", {"input1": "grain"}, intensity=0.8, inversedy=True, input2alpha=False)
    g.add("n_out", "normal_combine", {"input": "n_main", "input_1": "n_grain"})
    g.set_output("normal", "n_out")

    # ---- base colour ----------------------------------------------------------------------------
    g.add("variation", "gradient", {"input1": "tone_grain"},
          positions=[0.0, 0.5, 1.0],
          colors=[0.80, 0.80, 0.81, 1.0, 0.93, 0.925, 0.915, 1.0, 1.0, 0.99, 0.97, 1.0])
    g.add("tint", "uniform", outputcolor=[0.5, 0.49, 0.47, 1.0])
    g.bind("tint", "outputcolor", vector(get("color", 3), 1.0).graph())
    g.add("col_base", "blend", {"source": "variation", "destination": "tint"}, blendingmode=3)
    color_over(g, "col_stain", "stain_color", [0.78, 0.76, 0.72, 1.0], "col_base", mask="stains", blendingmode=3,
               opacitymult=0.5)
    g.add("dark", "uniform", outputcolor=[0.45, 0.44, 0.43, 1.0])
    g.add("cavities", "blend", {"source": "cracks", "destination": "pores_soft"}, blendingmode=5)
    g.add("col_out", "blend", {"source": "dark", "destination": "col_stain", "opacity": "cavities"},
          blendingmode=3, opacitymult=0.6)
    g.set_output("basecolor", "col_out")

    # ---- roughness ------------------------------------------------------------------------------
    g.add("r_base", "histogram_range", {"input": "tone_grain"}, range=0.08, position=0.86)
    g.bind("r_base", "position", get("roughness").graph())
    g.add("r_stain", "blend", {"source": "stains", "destination": "r_base"}, blendingmode=2, opacitymult=0.06)
    g.add("r_out", "blend", {"source": "cavities", "destination": "r_stain"}, blendingmode=1, opacitymult=0.1)
    g.set_output("roughness", "r_out")

    # ---- metallic, AO ---------------------------------------------------------------------------
    constant_map(g, "metal", 0.0)
    g.set_output("metallic", "metal")
    g.add("ao", "ambient_occlusion_2", {"source": "h_cracks"}, height_depth=0.12, spreading=0.1,
          model=OUR_OCCLUSION)
    g.set_output("ambientocclusion", "ao:ambient_occlusion")
    return g


FAMILY = "plaster"

SAMPLE_RANGES = {
    "exposed.color": ([0.40, 0.39, 0.37], [0.62, 0.61, 0.59]),
    "exposed.scale": (0.6, 1.8),
    "exposed.wear": (0.0, 0.9),
    "exposed.pores": (0.1, 0.9),
    "exposed.roughness": (0.72, 0.97),
    "exposed.relief": (0.25, 0.9),
    "tone.opacitymult": (0.2, 0.7),
    "tone_grain.opacitymult": (0.08, 0.3),
    "variation.colors": ([0.76, 0.76, 0.76, 1.0, 0.9, 0.9, 0.89, 1.0, 0.97, 0.97, 0.96, 1.0],
                         [0.84, 0.84, 0.84, 1.0, 0.95, 0.95, 0.94, 1.0, 1.0, 1.0, 0.99, 1.0]),
    "stain_color.outputcolor": ([0.72, 0.70, 0.66, 1.0], [0.84, 0.82, 0.78, 1.0]),
    "h_pores.opacitymult": (0.2, 0.7),
    "h_cracks.opacitymult": (0.15, 0.6),
}
