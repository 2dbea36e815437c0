"""Cork: agglomerated cork board or tile, compressed granules of varied tan-brown, small pores, matte.

Structure
- Granules: a Voronoi mosaic of random gray levels (Cells 4, about 48 granules across a 30 cm
  sample: the 3-8 mm granules of a notice board or floor tile), warped by a smooth noise so the
  pieces are irregular rather than convex polygons, with a finer mosaic (about twice as fine)
  mixed in: cork is crushed into granules of mixed sizes.
- Pores: the voids between compressed granules and the cork's own lenticels, taken as the darkest
  pieces of a fine mosaic (a histogram scan keeping all but a few percent as solid), plus fine pits
  of a thresholded spot noise; the solid masks are combined (min) and inverted into the pores.
- Height: granule levels (each piece pressed to a slightly different height) - pores + a fine
  grain; normal from it (OpenGL); ambient occlusion from the height.
- Colour: the exposed cork colour, each granule shifted along a tan-to-brown palette (light
  yellowish tan to reddish dark brown: the bark layers differ in density and age), the pores dark
  brown, a faint broad cloud so the board is not perfectly uniform.
- Roughness: matte, around the exposed roughness; pores rougher. Metallic 0.

Exposed parameters
- ``cork_color`` (float3): the average cork colour (tan by default).
- ``granule_contrast``: how much granules differ in colour.
- ``granule_size``: size of the granules (0 fine, 1 coarse).
- ``pores``: amount and depth of the pores.
- ``roughness``: the mean roughness (matte).
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD,
    ADD_SUB,
    MIN,
    MULTIPLY,
    SOFT_LIGHT,
    SUBTRACT,
    ao_darken,
    color_over,
    constant_map,
    gradient_over,
    normal_and_ao,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("cork")
    g.expose("cork_color", (0.55, 0.38, 0.24), min=0.0, max=1.0)
    g.expose("granule_contrast", 0.5, min=0.0, max=1.0)
    g.expose("granule_size", 0.5, min=0.0, max=1.0)
    g.expose("pores", 0.5, min=0.0, max=1.0)
    g.expose("roughness", 0.85, min=0.5, max=1.0)
    size = get("granule_size")

    # ---- granules ----------------------------------------------------------------------------
    g.add("flow", "clouds_1", seed=91, scale=6.0)
    g.add("coarse", "cells_4", seed=92, scale=48, disorder=0.9)
    g.bind("coarse", "scale", lerp(72.0, 30.0, size).graph())
    g.add("fine", "cells_4", seed=93, scale=100, disorder=0.9)
    g.bind("fine", "scale", lerp(140.0, 64.0, size).graph())
    g.add("mixed", "blend", {"source": "fine", "destination": "coarse"},
          blendingmode=ADD_SUB, opacitymult=0.35)
    g.add("granules", "warp", {"input1": "mixed", "inputgradient": "flow"}, intensity=0.05)

    # ---- pores -------------------------------------------------------------------------------
    g.add("voids_src", "warp", {"input1": "fine", "inputgradient": "flow"}, intensity=0.05)
    g.add("voids", "histogram_scan", {"input_1": "voids_src"}, position=0.08, contrast=0.85,
          invert_position=True)
    g.bind("voids", "position", lerp(0.0, 0.16, get("pores")).graph())
    g.add("pit_noise", "bnw_spots_3", seed=94, scale=24.0)
    g.add("pits", "histogram_scan", {"input_1": "pit_noise"}, position=0.12, contrast=0.6,
          invert_position=True)
    g.add("solid", "blend", {"source": "pits", "destination": "voids"},
          blendingmode=MIN, opacitymult=0.5)
    g.add("pores_all", "invert_grayscale", {"source": "solid"})

    # ---- height ------------------------------------------------------------------------------
    g.add("granule_level", "histogram_range", {"input": "granules"}, range=0.3, position=0.6)
    g.add("pored", "blend", {"source": "pores_all", "destination": "granule_level"},
          blendingmode=SUBTRACT, opacitymult=0.35)
    g.bind("pored", "opacitymult", lerp(0.1, 0.5, get("pores")).graph())
    g.add("grain", "white_noise", seed=95)
    g.add("grained", "blend", {"source": "grain", "destination": "pored"},
          blendingmode=ADD_SUB, opacitymult=0.05)
    g.add("height", "histogram_range", {"input": "grained"}, range=1.0, position=0.5)
    normal_and_ao(g, "height", intensity=2.5, height_depth=0.12, spreading=0.05)

    # ---- colour ------------------------------------------------------------------------------
    g.add("cork_base", "uniform", outputcolor=(0.55, 0.38, 0.24, 1.0))
    g.bind("cork_base", "outputcolor", vector(get("cork_color", 3), 1.0).graph())
    gradient_over(g, "cork_granules", "granule_tones", "granules", [
        (0.0, (0.30, 0.26, 0.24)), (0.3, (0.42, 0.39, 0.36)), (0.6, (0.54, 0.53, 0.50)),
        (1.0, (0.68, 0.66, 0.58))], "cork_base", blendingmode=SOFT_LIGHT, opacitymult=0.7)
    g.bind("cork_granules", "opacitymult", lerp(0.1, 1.0, get("granule_contrast")).graph())
    gradient_over(g, "cork_board", "board_tones", "flow", [(0.0, (0.44, 0.44, 0.44)), (1.0, (0.56, 0.55, 0.53))],
                  "cork_granules", blendingmode=SOFT_LIGHT, opacitymult=0.5)
    color_over(g, "cork_pores", "pore_color", (0.16, 0.09, 0.05, 1.0), "cork_board", mask="pores_all",
               blendingmode=MULTIPLY, opacitymult=0.8)
    ao_darken(g, "basecolor", "cork_pores", floor=0.3, opacitymult=0.35)

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_base", "histogram_range", {"input": "granules"}, range=0.08, position=0.85)
    g.bind("rough_base", "position", get("roughness").graph())
    g.add("roughness", "blend", {"source": "pores_all", "destination": "rough_base"},
          blendingmode=ADD, opacitymult=0.1)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "ground"

SAMPLE_RANGES = {
    "exposed.cork_color": ((0.42, 0.28, 0.14), (0.68, 0.46, 0.26)),
    "exposed.granule_contrast": (0.2, 0.9),
    "exposed.granule_size": (0.1, 0.9),
    "exposed.pores": (0.2, 0.8),
    "exposed.roughness": (0.7, 0.95),
    "coarse.disorder": (0.6, 1.0),
    "mixed.opacitymult": (0.15, 0.55),
    "granules.intensity": (0.0, 0.1),
    "voids_src.intensity": (0.0, 0.1),
    "pits.position": (0.05, 0.2),
    "normal.intensity": (1.5, 4.0),
    "granule_tones.colors": (
        (0.26, 0.22, 0.20, 1.0, 0.38, 0.35, 0.32, 1.0, 0.50, 0.49, 0.46, 1.0, 0.64, 0.62, 0.54, 1.0),
        (0.34, 0.30, 0.28, 1.0, 0.46, 0.43, 0.40, 1.0, 0.58, 0.57, 0.54, 1.0, 0.72, 0.70, 0.62, 1.0)),
}
