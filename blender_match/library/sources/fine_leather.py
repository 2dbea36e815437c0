"""Fine leather: smooth, fine-grain dyed leather (bags, shoes, wallets), semi-gloss finish.

Structure
- Grain: the hair-cell network of full-grain leather: thin grooves between flat cells (Cells 3, about
  44 cells across the sample, i.e. cells of 5-6 mm on a 25 cm sample) with low domes in each cell
  (Cells 1 with the same seed, multiplied in), warped by a smooth noise so the grooves meander and
  softened by a blur; a second, finer crack net
  (Cells 3, about twice as fine) is cut shallowly into the cushions so each cell is subdivided,
  as on real grain under a flash.
- Pores: small pits (a thresholded Gaussian Spots noise) sunk shallowly into the grain.
- Undulation: a very low, broad cloud so the surface is not perfectly planar (the soft folds of a
  bag panel).
- Height: grain cushions - fine cracks - pores + undulation; normal from it (OpenGL); ambient occlusion from the height.
- Colour: the exposed dye colour, mottled slightly by clouds (dye takes unevenly), darker in the
  grain grooves and pores where the dye pools, a touch lighter on the cushion tops.
- Roughness: semi-gloss around the exposed roughness; grooves and pores rougher (the finish is
  thinner there). Metallic 0.

Exposed parameters
- ``leather_color`` (float3): the dye colour (any: black, browns, tan, red, blue...).
- ``grain_depth``: depth of the hair-cell grain (height range, groove darkening).
- ``pores``: depth and darkness of the pores.
- ``mottling``: unevenness of the dye (opacity of the cloud tone).
- ``roughness``: mean roughness of the finish (semi-gloss by default).
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD,
    ADD_SUB,
    MULTIPLY,
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
    g = SbsGraph("fine_leather")
    g.expose("leather_color", (0.30, 0.15, 0.07), min=0.0, max=1.0)
    g.expose("grain_depth", 0.5, min=0.0, max=1.0)
    g.expose("pores", 0.4, min=0.0, max=1.0)
    g.expose("mottling", 0.4, min=0.0, max=1.0)
    g.expose("roughness", 0.36, min=0.15, max=0.9)

    # ---- grain -------------------------------------------------------------------------------
    g.add("flow", "clouds_1", seed=61, scale=5.0)
    g.add("grooves_src", "cells_3", seed=62, scale=44, disorder=0.8, width=0.09)
    g.add("domes_src", "cells_1", seed=62, scale=44, disorder=0.8)
    g.add("domed", "blend", {"source": "domes_src", "destination": "grooves_src"},
          blendingmode=MULTIPLY, opacitymult=0.3)
    g.add("domed_warp", "warp", {"input1": "domed", "inputgradient": "flow"}, intensity=0.04)
    g.add("cushions", "blur_hq_grayscale", {"source": "domed_warp"}, intensity=0.5)
    g.add("fine_cells", "cells_3", seed=63, scale=96, disorder=0.8, width=0.07)
    g.add("fine_warp", "warp", {"input1": "fine_cells", "inputgradient": "flow"}, intensity=0.05)
    g.add("fine_cracks", "invert_grayscale", {"source": "fine_warp"})
    g.add("pore_noise", "gaussian_spots_2", seed=64, scale=20.0)
    g.add("pore_pits", "histogram_scan", {"input_1": "pore_noise"}, position=0.9, contrast=0.8)

    # ---- height ------------------------------------------------------------------------------
    g.add("grain_level", "histogram_range", {"input": "cushions"}, range=0.5, position=0.55)
    g.bind("grain_level", "range", lerp(0.1, 0.9, get("grain_depth")).graph())
    g.add("cracked", "blend", {"source": "fine_cracks", "destination": "grain_level"},
          blendingmode=SUBTRACT, opacitymult=0.12)
    g.add("pored", "blend", {"source": "pore_pits", "destination": "cracked"},
          blendingmode=SUBTRACT, opacitymult=0.15)
    g.bind("pored", "opacitymult", lerp(0.0, 0.35, get("pores")).graph())
    g.add("undulation", "clouds_2", seed=65, scale=2.0)
    g.add("undulated", "blend", {"source": "undulation", "destination": "pored"},
          blendingmode=ADD_SUB, opacitymult=0.1)
    g.add("height", "histogram_range", {"input": "undulated"}, range=1.0, position=0.5)
    normal_and_ao(g, "height", intensity=1.4, height_depth=0.1, spreading=0.04)

    # ---- colour ------------------------------------------------------------------------------
    g.add("dye", "uniform", outputcolor=(0.30, 0.15, 0.07, 1.0))
    g.bind("dye", "outputcolor", vector(get("leather_color", 3), 1.0).graph())
    gradient_over(g, "dye_mottled", "mottle", "flow",
                  [(0.0, (0.40, 0.40, 0.40)), (0.5, (0.50, 0.50, 0.50)), (1.0, (0.60, 0.58, 0.56))], "dye",
                  blendingmode=SOFT_LIGHT, opacitymult=0.6)
    g.bind("dye_mottled", "opacitymult", get("mottling").graph())
    gradient_over(g, "dye_pooled", "groove_tones", "height",
                  [(0.0, (0.45, 0.44, 0.43)), (0.5, (0.85, 0.85, 0.85)), (1.0, (1.0, 1.0, 1.0))], "dye_mottled",
                  blendingmode=MULTIPLY, opacitymult=0.6)
    g.bind("dye_pooled", "opacitymult", lerp(0.2, 0.9, get("grain_depth")).graph())
    gradient_over(g, "dye_pores", "pore_tone", "pore_pits", [(0.0, (1.0, 1.0, 1.0)), (1.0, (0.55, 0.53, 0.52))],
                  "dye_pooled", blendingmode=MULTIPLY, opacitymult=0.5)
    g.bind("dye_pores", "opacitymult", lerp(0.0, 0.9, get("pores")).graph())
    g.add("top_tone", "uniform", outputcolor=(0.58, 0.56, 0.54, 1.0))
    g.add("tops", "histogram_scan", {"input_1": "height"}, position=0.7, contrast=0.4)
    g.add("dye_tops", "blend", {"source": "top_tone", "destination": "dye_pores", "opacity": "tops"},
          blendingmode=SOFT_LIGHT, opacitymult=0.4)
    ao_darken(g, "basecolor", "dye_tops", floor=0.35, opacitymult=0.3)

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_inv", "invert_grayscale", {"source": "height"})
    g.add("rough_base", "histogram_range", {"input": "rough_inv"}, range=0.12, position=0.36)
    g.bind("rough_base", "position", get("roughness").graph())
    g.add("roughness", "blend", {"source": "pore_pits", "destination": "rough_base"},
          blendingmode=ADD, opacitymult=0.12)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "leather"

SAMPLE_RANGES = {
    "exposed.leather_color": ((0.02, 0.02, 0.02), (0.85, 0.80, 0.78)),
    "exposed.grain_depth": (0.25, 0.85),
    "exposed.pores": (0.1, 0.8),
    "exposed.mottling": (0.1, 0.8),
    "exposed.roughness": (0.25, 0.65),
    "grooves_src.width": (0.05, 0.14),
    "domed_warp.intensity": (0.0, 0.08),
    "fine_warp.intensity": (0.0, 0.1),
    "domed.opacitymult": (0.1, 0.6),
    "cushions.intensity": (0.2, 1.0),
    "cracked.opacitymult": (0.03, 0.25),
    "normal.intensity": (0.8, 2.5),
    "mottle.colors": ((0.36, 0.36, 0.36, 1.0, 0.46, 0.46, 0.46, 1.0, 0.54, 0.52, 0.50, 1.0),
                      (0.44, 0.44, 0.44, 1.0, 0.54, 0.54, 0.54, 1.0, 0.64, 0.62, 0.60, 1.0)),
    "undulated.opacitymult": (0.0, 0.2),
}
