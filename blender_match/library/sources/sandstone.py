"""Sandstone: a sawn or rubbed sandstone face: fine sand grains, soft bedding bands, matte, a few pores.

Structure
- Bedding: soft stripes (the sedimentary layers) made irregular in thickness by a directional
  noise and wavy by a cloud warp; a gradient turns them into lighter and darker bands, and the
  harder (lighter, better cemented) layers stand a little proud in the height.
- Iron staining: a broad cloud noise tints the stone redder/browner in patches, as the iron
  oxides that colour sandstones are unevenly spread.
- Grain: white noise (one value a sand grain at this scale) softened a touch and mixed with a
  fine fractal noise: a salt-and-pepper of light quartz and dark lithic grains in the colour and a
  fine sandpaper relief in the height and normal.
- Pores: a few sparse small pits (thresholded white noise, blurred) sunk into the height and
  darkened in the colour (shadow and dirt inside).
- Roughness: very matte around the exposed level, pores and dark grains rougher. Metallic 0. AO
  from the height.

Exposed parameters
- ``sand_color`` (float3): the stone colour (cream, buff, yellow, ochre, pink, red-brown).
- ``bedding``: strength of the bedding bands in colour and height.
- ``grain``: strength of the sand grain (colour speckle and relief).
- ``pores``: how many pores.
- ``roughness``: the mean roughness.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD,
    ADD_SUB,
    MULTIPLY,
    OUR_OCCLUSION,
    OVERLAY,
    SUBTRACT,
    color_over,
    constant_map,
    gradient_over,
    pinned_keys,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph

BANDS = [(0.0, (0.38, 0.38, 0.38)), (0.35, (0.48, 0.48, 0.48)), (0.6, (0.53, 0.53, 0.53)),
         (1.0, (0.64, 0.64, 0.64))]
STAIN = [(0.0, (0.5, 0.5, 0.5)), (0.6, (0.52, 0.49, 0.46)), (1.0, (0.58, 0.44, 0.36))]
AO_TONE = [(0.0, (0.5, 0.5, 0.5)), (1.0, (1.0, 1.0, 1.0))]
GRAINS = [(0.0, (0.2, 0.2, 0.2)), (0.12, (0.42, 0.42, 0.42)), (0.5, (0.5, 0.5, 0.5)), (0.88, (0.58, 0.58, 0.58)),
          (1.0, (0.8, 0.8, 0.8))]


def build() -> SbsGraph:
    g = SbsGraph("sandstone")
    g.expose("sand_color", (0.74, 0.60, 0.42), min=0.0, max=1.0)
    g.expose("bedding", 0.5, min=0.0, max=1.0)
    g.expose("grain", 0.5, min=0.0, max=1.0)
    g.expose("pores", 0.35, min=0.0, max=1.0)
    g.expose("roughness", 0.85, min=0.5, max=1.0)

    # ---- bedding ------------------------------------------------------------------------------
    g.add("layers", "stripes", number=5, width=0.5, softness=1.0, shift=0)
    g.add("layers_h", "transformation", {"input1": "layers"}, matrix22=(0.0, 1.0, 1.0, 0.0))
    g.add("layer_var", "clouds_1", seed=71, scale=3.0)
    g.add("layers_var", "directionalwarp", {"input1": "layers_h", "inputintensity": "layer_var"},
          intensity=12.0, warpangle=0.25)
    g.add("wave", "clouds_1", seed=72, scale=2.0)
    g.add("layers_wavy", "warp", {"input1": "layers_var", "inputgradient": "wave"}, intensity=0.3)
    g.add("bands", "blur_hq_grayscale", {"source": "layers_wavy"}, intensity=3.0)
    g.add("band_fade", "clouds_2", seed=77, scale=1.0)

    # ---- grain and pores ----------------------------------------------------------------------
    g.add("sand_noise", "white_noise", seed=73)
    g.add("sand_soft", "blur", {"input1": "sand_noise"}, intensity=0.25)
    g.add("sand_fine", "fractal_sum_4", seed=74, scale=4.0)
    g.add("sand", "blend", {"source": "sand_fine", "destination": "sand_soft"}, blendingmode=ADD_SUB,
          opacitymult=0.15)
    g.add("pore_noise", "white_noise", seed=75)
    g.add("pore_seeds", "histogram_scan", {"input_1": "pore_noise"}, position=0.004, contrast=0.9)
    g.bind("pore_seeds", "position", lerp(0.0, 0.003, get("pores")).graph())
    g.add("pores", "blur_hq_grayscale", {"source": "pore_seeds"}, intensity=1.2)
    g.add("pores_mask", "histogram_scan", {"input_1": "pores"}, position=0.95, contrast=0.5)

    # ---- height -------------------------------------------------------------------------------
    g.add("h_bands", "histogram_range", {"input": "bands"}, range=0.2, position=0.5)
    g.bind("h_bands", "range", lerp(0.0, 0.25, get("bedding")).graph())
    g.add("h_grain", "blend", {"source": "sand", "destination": "h_bands"}, blendingmode=ADD_SUB,
          opacitymult=0.1)
    g.bind("h_grain", "opacitymult", lerp(0.02, 0.2, get("grain")).graph())
    g.add("h_pores", "blend", {"source": "pores_mask", "destination": "h_grain"}, blendingmode=SUBTRACT,
          opacitymult=0.35)
    g.add("height", "histogram_range", {"input": "h_pores"}, range=1.0, position=0.5)
    g.add("normal", "normal", {"input1": "height"}, intensity=5.0, inversedy=True, input2alpha=False)
    g.add("ao", "ambient_occlusion_2", {"source": "height"}, height_depth=0.1, spreading=0.05,
          model=OUR_OCCLUSION)

    # ---- colour -------------------------------------------------------------------------------
    g.add("sand_base", "uniform", outputcolor=(0.74, 0.60, 0.42, 1.0))
    g.bind("sand_base", "outputcolor", vector(get("sand_color", 3), 1.0).graph())
    gradient_over(g, "col_bands", "band_tone", "bands", BANDS, "sand_base", mask="band_fade", blendingmode=ADD_SUB,
                  opacitymult=0.5)
    g.bind("col_bands", "opacitymult", lerp(0.0, 1.0, get("bedding")).graph())
    g.add("stain_noise", "clouds_2", seed=76, scale=1.5)
    gradient_over(g, "col_stain", "stain", "stain_noise", STAIN, "col_bands", blendingmode=OVERLAY, opacitymult=0.6)
    gradient_over(g, "col_grain", "grain_tone", "sand", GRAINS, "col_stain", blendingmode=ADD_SUB, opacitymult=0.4)
    g.bind("col_grain", "opacitymult", lerp(0.05, 0.7, get("grain")).graph())
    color_over(g, "col_pores", "pore_color", (0.22, 0.18, 0.14, 1.0), "col_grain", mask="pores_mask",
               blendingmode=MULTIPLY, opacitymult=0.5)
    gradient_over(g, "basecolor", "ao_tone", "ao", AO_TONE, "col_pores", blendingmode=MULTIPLY, opacitymult=0.3)

    # ---- roughness ----------------------------------------------------------------------------
    g.add("r_base", "histogram_range", {"input": "sand"}, range=0.08, position=0.85)
    g.bind("r_base", "position", get("roughness").graph())
    g.add("roughness", "blend", {"source": "pores_mask", "destination": "r_base"}, blendingmode=ADD,
          opacitymult=0.15)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "stone"


SAMPLE_RANGES = {
    "exposed.sand_color": ((0.62, 0.4, 0.24), (0.88, 0.66, 0.48)),
    "exposed.bedding": (0.1, 0.9),
    "exposed.grain": (0.2, 0.8),
    "exposed.pores": (0.0, 0.8),
    "exposed.roughness": (0.75, 0.98),
    "layers_var.intensity": (4.0, 20.0),
    "layers_var.warpangle": (0.22, 0.28),
    "pores.intensity": (0.8, 1.6),
    "sand_fine.scale": (3.0, 6.0),
    "layers_wavy.intensity": (0.1, 0.6),
    "bands.intensity": (1.5, 5.0),
    "col_stain.opacitymult": (0.2, 0.9),
    "sand_soft.intensity": (0.0, 0.5),
    "normal.intensity": (2.5, 8.0),
    "pore_color.outputcolor": ((0.18, 0.15, 0.12, 1.0), (0.32, 0.27, 0.22, 1.0)),
    **{f"{node}.{p}": r for node, stops in (("band_tone", BANDS), ("stain", STAIN), ("grain_tone", GRAINS),
                                             ("ao_tone", AO_TONE))
       for p, r in pinned_keys(stops).items()},
}
