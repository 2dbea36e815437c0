"""Leather: full-grain, dyed cowhide (upholstery/bag leather) with a pebbled grain and wrinkles.

Structure
- Grain: a fine Voronoi-like cell pattern (Cells 1) warped by a cloud noise so the pebbles are
  irregular, shaped into rounded domes with a histogram scan, their heights varied by a fine
  Perlin noise; tiny pores (BnW Spots 3) sink into it.
- Wrinkles: thin crease lines taken as an iso-line band of the Creased generator (histogram
  select), warped, blurred, and cut into the grain (depth exposed), plus the generator's broad
  folds as a low-frequency undulation.
- Height: grain domes + folds - wrinkles - pores; normal from it (OpenGL) combined with a pore
  detail normal; ambient occlusion from the height.
- Colour: the exposed leather colour, darkened in the grain valleys and wrinkles (the dye pools),
  mottled by clouds, and lightened/desaturated on the pebble tops where the finish is rubbed
  (exposed wear).
- Roughness: semi-matte around the exposed roughness, valleys rougher, rubbed tops glossier.
  Metallic 0.

Exposed parameters
- ``leather_color`` (float3): the dye colour.
- ``grain_depth``: strength of the pebble grain in the height (and so the normal).
- ``wrinkles``: depth of the crease lines.
- ``wear``: rubbed, lighter and glossier pebble tops.
- ``roughness``: mean roughness of the finish.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD,
    ADD_SUB,
    MULTIPLY,
    OUR_OCCLUSION,
    OVERLAY,
    SOFT_LIGHT,
    SUBTRACT,
    ao_darken,
    color_over,
    constant_map,
    gradient_over,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("leather")
    g.expose("leather_color", (0.30, 0.15, 0.08), min=0.0, max=1.0)
    g.expose("grain_depth", 0.5, min=0.0, max=1.0)
    g.expose("wrinkles", 0.45, min=0.0, max=1.0)
    g.expose("wear", 0.3, min=0.0, max=1.0)
    g.expose("roughness", 0.55, min=0.2, max=0.95)

    # ---- grain -------------------------------------------------------------------------------
    g.add("cells", "cells_1", seed=41, scale=40, disorder=0.6)
    g.add("fold_noise", "clouds_1", seed=45, scale=4.0)
    g.add("cells_warp", "warp", {"input1": "cells", "inputgradient": "fold_noise"}, intensity=0.05)
    g.add("pebbles", "histogram_scan", {"input_1": "cells_warp"}, position=0.6, contrast=0.15)
    g.add("pores_noise", "bnw_spots_3", seed=43, scale=20.0)
    g.add("pores", "histogram_scan", {"input_1": "pores_noise"}, position=0.2, contrast=0.5, invert_position=True)

    # ---- wrinkles and folds ------------------------------------------------------------------
    g.add("creased", "creased", seed=44, scale=3, disorder=0.3, folds=10)
    g.add("creased_warp", "warp", {"input1": "creased", "inputgradient": "fold_noise"}, intensity=0.15)
    g.add("crease_lines", "histogram_select", {"input": "creased_warp"}, position=0.45, range=0.01, contrast=0.93)
    g.add("crease_soft", "blur_hq_grayscale", {"source": "crease_lines"}, intensity=0.8)

    # ---- height ------------------------------------------------------------------------------
    g.add("pebble_noise", "perlin_noise_1", seed=42, scale=32.0)
    g.add("pebbles_varied", "blend", {"source": "pebble_noise", "destination": "pebbles"},
          blendingmode=MULTIPLY, opacitymult=0.35)
    g.add("grain_level", "histogram_range", {"input": "pebbles_varied"}, range=0.5, position=0.6)
    g.bind("grain_level", "range", lerp(0.1, 0.9, get("grain_depth")).graph())
    g.add("folded", "blend", {"source": "creased_warp", "destination": "grain_level"},
          blendingmode=ADD_SUB, opacitymult=0.08)
    g.add("wrinkled", "blend", {"source": "crease_soft", "destination": "folded"},
          blendingmode=SUBTRACT, opacitymult=0.35)
    g.bind("wrinkled", "opacitymult", lerp(0.0, 0.7, get("wrinkles")).graph())
    g.add("pored", "blend", {"source": "pores", "destination": "wrinkled"},
          blendingmode=SUBTRACT, opacitymult=0.06)
    g.add("height", "histogram_range", {"input": "pored"}, range=1.0, position=0.5)
    g.add("normal_main", "normal", {"input1": "height"}, intensity=3.0, inversedy=True)
    g.add("normal_pores", "normal", {"input1": "pores_noise"}, intensity=0.3, inversedy=True)
    g.add("normal", "normal_combine", {"input": "normal_main", "input_1": "normal_pores"})
    g.add("ao", "ambient_occlusion_2", {"source": "height"}, height_depth=0.15, spreading=0.05,
          model=OUR_OCCLUSION)

    # ---- colour ------------------------------------------------------------------------------
    g.add("dye", "uniform", outputcolor=(0.30, 0.15, 0.08, 1.0))
    g.bind("dye", "outputcolor", vector(get("leather_color", 3), 1.0).graph())
    gradient_over(g, "dye_mottled", "mottle", "fold_noise", [(0.0, (0.40, 0.40, 0.40)), (1.0, (0.60, 0.57, 0.54))],
                  "dye", blendingmode=SOFT_LIGHT, opacitymult=0.7)
    gradient_over(g, "dye_pooled", "valley_tones", "height",
                  [(0.0, (0.35, 0.33, 0.32)), (0.45, (0.78, 0.77, 0.76)), (1.0, (1.0, 1.0, 1.0))], "dye_mottled",
                  blendingmode=MULTIPLY, opacitymult=0.8)
    g.add("tops", "histogram_scan", {"input_1": "height"}, position=0.3, contrast=0.3)
    g.bind("tops", "position", lerp(0.0, 0.6, get("wear")).graph())
    color_over(g, "rubbed", "rub_color", (0.62, 0.52, 0.44, 1.0), "dye_pooled", mask="tops", blendingmode=OVERLAY,
               opacitymult=0.5)
    ao_darken(g, "basecolor", "rubbed", floor=0.3, opacitymult=0.4)

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_base", "histogram_range", {"input": "height"}, range=0.15, position=0.55)
    g.bind("rough_base", "position", get("roughness").graph())
    g.add("rough_inv", "invert_grayscale", {"source": "rough_base"})
    g.add("rough_rubbed", "blend", {"source": "tops", "destination": "rough_inv"},
          blendingmode=SUBTRACT, opacitymult=0.12)
    g.add("roughness", "blend", {"source": "crease_soft", "destination": "rough_rubbed"},
          blendingmode=ADD, opacitymult=0.1)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "leather"

SAMPLE_RANGES = {
    "exposed.leather_color": ((0.03, 0.03, 0.03), (0.85, 0.80, 0.75)),
    "exposed.grain_depth": (0.2, 0.9),
    "exposed.wrinkles": (0.0, 0.9),
    "exposed.wear": (0.0, 0.8),
    "exposed.roughness": (0.35, 0.8),
    "cells.disorder": (0.3, 0.9),
    "cells_warp.intensity": (0.0, 0.12),
    "pebbles.position": (0.45, 0.75),
    "normal_main.intensity": (1.5, 6.0),
    "dye_mottled.opacitymult": (0.3, 1.0),
    "dye_pooled.opacitymult": (0.4, 1.0),
}
