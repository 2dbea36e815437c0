"""Rough stone: a split, roughly hewn natural rock face (sandstone / granite-like).

Structure
- Height: chunky faceted relief (crystal noise for flat fractured facets) over a large clouds
  undulation, chipped by a min-mode slope blur along a fractal noise (sharp breaks), plus a fine
  fractal grit; deep fissures from warped cell borders.
- Base colour: a three-key stone palette mapped from the relief and a mineral speckle (white noise
  threshold), multiplied by the exposed tint; dirt / weathering settles in the crevices (a histogram
  scan of the inverted height), tinted brown.
- Roughness: very rough, a bit higher in the dirty crevices.
- Normal: from the height (OpenGL) combined with a grit detail normal. Metallic 0; AO from height.

Exposed parameters
- ``color`` (float3, sRGB): the stone tint.
- ``scale``: how many chunks per tile.
- ``relief``: depth of the relief (normal strength and chipping).
- ``weathering``: dirt in the crevices and colour fading.
- ``roughness``: the mean roughness.
"""
from __future__ import annotations

from blender_match.library.authoring import OUR_OCCLUSION, color_over, constant_map
from blender_match.library.expressions import clamp, get, lerp, vector
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("rough_stone")
    g.expose("color", [0.78, 0.74, 0.68], min=0.0, max=1.0)
    g.expose("scale", 1.0, min=0.5, max=2.0)
    g.expose("relief", 0.6, min=0.0, max=1.0)
    g.expose("weathering", 0.4, min=0.0, max=1.0)
    g.expose("roughness", 0.88, min=0.6, max=1.0)
    scale = get("scale")
    relief = get("relief")
    weathering = get("weathering")

    # ---- generators -------------------------------------------------------------------------
    g.add("facets", "crystal_1", seed=41, scale=3.0)
    g.bind("facets", "scale", (scale * 3.0).graph())
    g.add("big", "clouds_2", seed=42, scale=2.0)
    g.add("grit", "fractal_sum_1", seed=43, scale=8.0, roughness=0.65)
    g.bind("grit", "scale", clamp(scale * 8.0, 1.0, 32.0).graph())
    g.add("cells", "cells_3", seed=44, scale=4, width=0.06, disorder=0.6)
    g.add("speck", "white_noise", seed=45)

    # ---- relief -----------------------------------------------------------------------------------
    g.add("chunks", "blend", {"source": "facets", "destination": "big"}, blendingmode=0, opacitymult=0.6)
    g.add("chipped", "slope_blur_grayscale", {"source": "chunks", "effect": "grit"}, samples=4, mode=6,
          intensity=3.0)
    g.bind("chipped", "intensity", lerp(0.5, 5.0, relief).graph())
    g.add("h_grit", "blend", {"source": "grit", "destination": "chipped"}, blendingmode=4, opacitymult=0.12)
    g.add("fissure_warp", "warp", {"input1": "cells", "inputgradient": "big"}, intensity=0.4)
    g.add("fissures", "histogram_scan", {"input_1": "fissure_warp"}, position=0.82, contrast=0.5)
    g.add("h_fiss", "blend", {"source": "fissures", "destination": "h_grit"}, blendingmode=3, opacitymult=0.5)
    g.add("height", "histogram_range", {"input": "h_fiss"}, range=0.9, position=0.5)
    g.set_output("height", "height")

    # ---- normal ---------------------------------------------------------------------------------
    g.add("n_main", "normal", {"input1": "height"}, intensity=8.0, inversedy=True, input2alpha=False)
    g.bind("n_main", "intensity", lerp(1.0, 16.0, relief).graph())
    g.add("n_grit", "normal", {"input1": "grit"}, intensity=1.5, inversedy=True, input2alpha=False)
    g.add("n_out", "normal_combine", {"input": "n_main", "input_1": "n_grit"})
    g.set_output("normal", "n_out")

    # ---- colour -----------------------------------------------------------------------------------
    g.add("speck_mask", "histogram_scan", {"input_1": "speck"}, position=0.1, contrast=0.8)
    g.add("speck_soft", "blur", {"input1": "speck_mask"}, intensity=0.4)
    g.add("shade", "blend", {"source": "facets", "destination": "big"}, blendingmode=4, opacitymult=0.35)
    g.add("palette", "gradient", {"input1": "shade"},
          positions=[0.0, 0.5, 1.0],
          colors=[0.42, 0.40, 0.37, 1.0, 0.62, 0.59, 0.55, 1.0, 0.78, 0.75, 0.70, 1.0])
    g.add("tint", "uniform", outputcolor=[0.78, 0.74, 0.68, 1.0])
    g.bind("tint", "outputcolor", vector(get("color", 3), 1.0).graph())
    g.add("col_base", "blend", {"source": "palette", "destination": "tint"}, blendingmode=3)
    color_over(g, "col_speck", "speck_color", [0.12, 0.11, 0.10, 1.0], "col_base", mask="speck_soft", blendingmode=0,
               opacitymult=0.7)
    g.add("crevice_src", "invert_grayscale", {"source": "height"})
    g.add("crevices", "histogram_scan", {"input_1": "crevice_src"}, position=0.4, contrast=0.3)
    g.bind("crevices", "position", lerp(0.03, 0.55, weathering).graph())
    color_over(g, "col_out", "dirt_color", [0.30, 0.25, 0.19, 1.0], "col_speck", mask="crevices", blendingmode=0,
               opacitymult=0.55)
    g.set_output("basecolor", "col_out")

    # ---- roughness ------------------------------------------------------------------------------
    g.add("r_base", "histogram_range", {"input": "grit"}, range=0.1, position=0.88)
    g.bind("r_base", "position", get("roughness").graph())
    g.add("r_out", "blend", {"source": "crevices", "destination": "r_base"}, blendingmode=1, opacitymult=0.06)
    g.set_output("roughness", "r_out")

    # ---- metallic, AO ---------------------------------------------------------------------------
    constant_map(g, "metal", 0.0)
    g.set_output("metallic", "metal")
    g.add("ao", "ambient_occlusion_2", {"source": "height"}, height_depth=0.2, spreading=0.15,
          model=OUR_OCCLUSION)
    g.set_output("ambientocclusion", "ao:ambient_occlusion")
    return g


FAMILY = "stone"

SAMPLE_RANGES = {
    "exposed.color": ([0.70, 0.66, 0.60], [0.88, 0.84, 0.78]),
    "exposed.scale": (0.6, 1.8),
    "exposed.relief": (0.3, 1.0),
    "exposed.weathering": (0.0, 0.9),
    "exposed.roughness": (0.75, 0.98),
    "palette.colors": ([0.25, 0.23, 0.2, 1.0, 0.45, 0.42, 0.38, 1.0, 0.62, 0.6, 0.55, 1.0],
                       [0.55, 0.53, 0.5, 1.0, 0.75, 0.72, 0.68, 1.0, 0.92, 0.9, 0.86, 1.0]),
    "chunks.opacitymult": (0.3, 0.85),
    "shade.opacitymult": (0.15, 0.6),
    "col_speck.opacitymult": (0.2, 0.9),
    "speck_mask.position": (0.03, 0.25),
    "h_fiss.opacitymult": (0.1, 0.8),
    "dirt_color.outputcolor": ([0.18, 0.14, 0.1, 1.0], [0.45, 0.4, 0.33, 1.0]),
}
