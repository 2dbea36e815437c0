"""Material: moulded textured plastic (appliance housing, car interior trim) with a fine stipple or leather-like grain.

Structure
- Stipple: a dense Gaussian-spot noise shaped by a histogram scan into small rounded bumps, on
  a finer Perlin speckle: the spark-eroded texture of a mould.
- Leather-like grain: a fine cell pattern (Cells 1) warped by clouds so the cells are irregular,
  domed by a histogram scan, the "grain" imitation of dashboards. The exposed grain type
  cross-fades stipple (0) and leather grain (1).
- Height: the chosen texture, its depth exposed, over a very faint broad undulation (moulded parts
  are not perfectly flat); normal from it, ambient occlusion from the height.
- Colour: the exposed plastic colour (mass-coloured, so almost uniform): a touch lighter on the
  bump tops, darker in the valleys where dust settles, and a faint cloud mottle.
- Roughness: moderate around the exposed roughness; valleys rougher; bump tops polished
  smoother by handling where the exposed wear says so. Metallic 0.

Exposed parameters
- ``plastic_color`` (float3): the plastic's colour (any colour).
- ``grain_depth``: depth of the texture in the height (and so the normal).
- ``grain_type``: 0 fine stipple, 1 leather-like grain, in between a mix.
- ``roughness``: mean roughness of the surface.
- ``wear``: polished, glossier bump tops where hands rub.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD_SUB,
    MULTIPLY,
    OVERLAY,
    SOFT_LIGHT,
    SUBTRACT,
    ao_darken,
    constant_map,
    gradient_over,
    normal_and_ao,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("textured_plastic")
    g.expose("plastic_color", (0.12, 0.12, 0.13), min=0.0, max=1.0)
    g.expose("grain_depth", 0.5, min=0.0, max=1.0)
    g.expose("grain_type", 0.3, min=0.0, max=1.0)
    g.expose("roughness", 0.55, min=0.2, max=0.95)
    g.expose("wear", 0.2, min=0.0, max=1.0)

    # ---- stipple -----------------------------------------------------------------------------
    g.add("stipple_spots", "gaussian_spots_1", seed=81, scale=7.0)
    g.add("stipple_bumps", "histogram_scan", {"input_1": "stipple_spots"}, position=0.45, contrast=0.2)
    g.add("speckle", "perlin_noise", seed=82, scale=64.0)
    g.add("stipple_mix", "blend", {"source": "speckle", "destination": "stipple_bumps"},
          blendingmode=OVERLAY, opacitymult=0.35)
    g.add("stipple", "blur", {"input1": "stipple_mix"}, intensity=0.7)

    # ---- leather-like grain ------------------------------------------------------------------
    g.add("grain_cells", "cells_1", seed=83, scale=56, disorder=0.7)
    g.add("grain_clouds", "clouds_1", seed=84, scale=5.0)
    g.add("grain_warp", "warp", {"input1": "grain_cells", "inputgradient": "grain_clouds"}, intensity=0.06)
    g.add("grain_domes", "histogram_scan", {"input_1": "grain_warp"}, position=0.45, contrast=0.1)
    g.add("grain", "blend", {"source": "speckle", "destination": "grain_domes"},
          blendingmode=OVERLAY, opacitymult=0.2)

    g.add("texture", "blend", {"source": "grain", "destination": "stipple"}, opacitymult=0.3)
    g.bind("texture", "opacitymult", get("grain_type").graph())

    # ---- height ------------------------------------------------------------------------------
    g.add("texture_level", "histogram_range", {"input": "texture"}, range=0.5, position=0.55)
    g.bind("texture_level", "range", lerp(0.05, 0.9, get("grain_depth")).graph())
    g.add("undulation", "clouds_2", seed=85, scale=1.0)
    g.add("height", "blend", {"source": "undulation", "destination": "texture_level"},
          blendingmode=ADD_SUB, opacitymult=0.06)
    normal_and_ao(g, "height", intensity=1.8, height_depth=0.1, spreading=0.04)

    # ---- colour ------------------------------------------------------------------------------
    g.add("plastic", "uniform", outputcolor=(0.12, 0.12, 0.13, 1.0))
    g.bind("plastic", "outputcolor", vector(get("plastic_color", 3), 1.0).graph())
    gradient_over(g, "plastic_mottled", "mottle", "undulation", [(0.0, (0.46, 0.46, 0.46)), (1.0, (0.54, 0.54, 0.54))],
                  "plastic", blendingmode=SOFT_LIGHT, opacitymult=0.5)
    gradient_over(g, "plastic_relief", "relief_tone", "texture",
                  [(0.0, (0.78, 0.78, 0.78)), (0.6, (0.95, 0.95, 0.95)), (1.0, (1.0, 1.0, 1.0))], "plastic_mottled",
                  blendingmode=MULTIPLY, opacitymult=0.8)
    ao_darken(g, "basecolor", "plastic_relief", floor=0.4, opacitymult=0.4, color_name="ao_tone")

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_base", "histogram_range", {"input": "texture"}, range=0.12, position=0.55)
    g.bind("rough_base", "position", get("roughness").graph())
    g.add("rough_inv", "invert_grayscale", {"source": "rough_base"})
    g.add("tops", "histogram_scan", {"input_1": "height"}, position=0.2, contrast=0.4)
    g.bind("tops", "position", lerp(0.0, 0.5, get("wear")).graph())
    g.add("roughness", "blend", {"source": "tops", "destination": "rough_inv"},
          blendingmode=SUBTRACT, opacitymult=0.2)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "coating"

SAMPLE_RANGES = {
    "exposed.plastic_color": ((0.02, 0.02, 0.02), (0.9, 0.9, 0.9)),
    "exposed.grain_depth": (0.2, 0.9),
    "exposed.grain_type": (0.0, 1.0),
    "exposed.roughness": (0.35, 0.8),
    "exposed.wear": (0.0, 0.6),
    "stipple_spots.scale": (5.0, 10.0),
    "stipple_bumps.position": (0.3, 0.6),
    "stipple_mix.opacitymult": (0.15, 0.6),
    "grain_cells.disorder": (0.4, 0.9),
    "grain_warp.intensity": (0.0, 0.12),
    "normal.intensity": (1.0, 4.0),
    "plastic_relief.opacitymult": (0.4, 1.0),
}
