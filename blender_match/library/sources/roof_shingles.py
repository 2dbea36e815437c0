"""Roof shingles: overlapping slate, clay or asphalt shingles in staggered rows, shadowed under each row's edge.

Structure
- Layout: a linear gradient repeated once per row (5 rows, so about 6 cm exposed per row on a
  30 cm sample; turned to rise downwards) times a Brick Generator mask (4 shingles across,
  alternate rows shifted half a shingle, a narrow vertical gap bound to the exposed gap width),
  and the product warped (below): every shingle rises from its top, where it slides under the
  row above, to its thick bottom edge lying on the row below; the sharp drop at each bottom edge
  is the row step. A flat twin brick generator of the same seed with full luminance randomness is
  the shingle id. (A Tile Generator "gradation" turned a quarter turn does not work here: in a
  non-square cell the turned shape no longer fills the cell.)
- The layout is warped by a fractal noise so the edges are hand-cut, not ruler-straight; a blotchy
  noise subtracted from the ramps dents the faces a little (worn, flaked spots).
- Only rectangular shingles (slate, plain clay tiles, 3-tab asphalt at a small scale): no
  fish-scale variant.
- Surface: a horizontal anisotropic noise (slate cleavage, asphalt streaks) and a fine speckle
  (mineral granules of asphalt shingles, sandy clay) in the height, scaled by the exposed grit.
- Height: ramps (with the exposed depth) + per-shingle offset + surface; normal from it (OpenGL)
  with a granule detail normal; ambient occlusion gives the shadow band under each edge.
- Colour: the exposed shingle colour, a per-shingle tone (soft light of a gradient of the id,
  exposed variation), clouds and granule speckle; darkened just under each row's edge (the
  shadow band) and by occlusion.
- Roughness: matte around the exposed roughness, granules rougher. Metallic 0.

Exposed parameters
- ``shingle_color`` (float3): the mean colour (slate gray-blue, clay red, asphalt black/brown/green).
- ``color_variation``: how much shingles differ from one another.
- ``row_depth``: how thick the shingles are: the height of the row step and its shadow band.
- ``gap_width``: width of the vertical gaps between shingles of a row.
- ``grit``: granule/cleavage texture on the faces (asphalt grit, slate riven surface).
- ``roughness``: mean roughness.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD_SUB,
    MULTIPLY,
    OUR_OCCLUSION,
    OVERLAY,
    SOFT_LIGHT,
    SUBTRACT,
    ao_darken,
    constant_map,
    gradient_over,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph

NX, NY = 4, 5


def build() -> SbsGraph:
    g = SbsGraph("roof_shingles")
    g.expose("shingle_color", (0.24, 0.25, 0.28), min=0.0, max=1.0)
    g.expose("color_variation", 0.5, min=0.0, max=1.0)
    g.expose("row_depth", 0.5, min=0.0, max=1.0)
    g.expose("gap_width", 0.04, min=0.0, max=0.15)
    g.expose("grit", 0.4, min=0.0, max=1.0)
    g.expose("roughness", 0.75, min=0.3, max=1.0)

    # ---- layout ------------------------------------------------------------------------------
    g.add("rows", "gradient_linear_1", tiling=NY, rotation=0.5)
    g.add("bricks", "brick_generator", seed=61, x_amount=NX, y_amount=NY, offset=0.5,
          interstice=(0.04, 0.0), bevel=0.02, luminance_random=0.0)
    g.bind("bricks", "interstice", vector(get("gap_width"), 0.0).graph())
    g.add("ramps", "blend", {"source": "rows", "destination": "bricks"},
          blendingmode=MULTIPLY, opacitymult=1.0)
    g.add("shingle_id", "brick_generator", seed=61, x_amount=NX, y_amount=NY, offset=0.5,
          interstice=(0.0, 0.0), bevel=0.0, luminance_random=1.0)
    g.add("edge_noise", "fractal_sum_1", seed=62, scale=8.0, roughness=0.5)
    g.add("ramps_warp", "warp", {"input1": "ramps", "inputgradient": "edge_noise"}, intensity=0.03)
    g.add("id_warp", "warp", {"input1": "shingle_id", "inputgradient": "edge_noise"}, intensity=0.03)

    # chips: blotches bite into the thin (low) top of each shingle's ramp, the edges stay whole
    g.add("chips_noise", "bnw_spots_1", seed=63, scale=8.0)
    g.add("ramps_chipped", "blend", {"source": "chips_noise", "destination": "ramps_warp"},
          blendingmode=SUBTRACT, opacitymult=0.12)
    g.add("ramps_soft", "blur_hq_grayscale", {"source": "ramps_chipped"}, intensity=0.6)

    # ---- surface -----------------------------------------------------------------------------
    g.add("cleavage", "anisotropic_noise", seed=64, x_amount=6, y_amount=96, smoothness=0.5)
    g.add("granules", "bnw_spots_3", seed=65, scale=24.0)
    g.add("surface", "blend", {"source": "granules", "destination": "cleavage"},
          blendingmode=ADD_SUB, opacitymult=0.5)

    # ---- height ------------------------------------------------------------------------------
    g.add("ramp_level", "histogram_range", {"input": "ramps_soft"}, range=0.6, position=0.5)
    g.bind("ramp_level", "range", lerp(0.15, 0.95, get("row_depth")).graph())
    g.add("offset", "histogram_range", {"input": "id_warp"}, range=0.1, position=0.5)
    g.add("shingles", "blend", {"source": "offset", "destination": "ramp_level"},
          blendingmode=ADD_SUB, opacitymult=0.5)
    g.add("gritty", "blend", {"source": "surface", "destination": "shingles"},
          blendingmode=ADD_SUB, opacitymult=0.06)
    g.bind("gritty", "opacitymult", lerp(0.0, 0.12, get("grit")).graph())
    g.add("height", "histogram_range", {"input": "gritty"}, range=1.0, position=0.5)

    g.add("normal_main", "normal", {"input1": "height"}, intensity=4.0, inversedy=True)
    g.add("normal_grit", "normal", {"input1": "granules"}, intensity=0.4, inversedy=True)
    g.add("normal", "normal_combine", {"input": "normal_main", "input_1": "normal_grit"})
    g.add("ao", "ambient_occlusion_2", {"source": "height"}, height_depth=0.2, spreading=0.12,
          model=OUR_OCCLUSION)

    # ---- colour ------------------------------------------------------------------------------
    g.add("base", "uniform", outputcolor=(0.24, 0.25, 0.28, 1.0))
    g.bind("base", "outputcolor", vector(get("shingle_color", 3), 1.0).graph())
    gradient_over(g, "varied", "shingle_tones", "id_warp",
                  [(0.0, (0.30, 0.30, 0.31)), (0.4, (0.47, 0.47, 0.48)), (1.0, (0.68, 0.66, 0.62))], "base",
                  blendingmode=SOFT_LIGHT, opacitymult=0.5)
    g.bind("varied", "opacitymult", get("color_variation").graph())
    g.add("clouds", "clouds_2", seed=66, scale=3.0)
    gradient_over(g, "clouded", "cloud_tones", "clouds", [(0.0, (0.40, 0.40, 0.40)), (1.0, (0.60, 0.59, 0.57))],
                  "varied", blendingmode=SOFT_LIGHT, opacitymult=0.6)
    gradient_over(g, "gritted", "grit_tones", "surface", [(0.0, (0.30, 0.30, 0.30)), (1.0, (0.68, 0.68, 0.66))],
                  "clouded", blendingmode=OVERLAY, opacitymult=0.3)
    g.bind("gritted", "opacitymult", lerp(0.05, 0.6, get("grit")).graph())
    # the shadow band: the low (top) part of each ramp sits under the row above
    gradient_over(g, "shadowed", "shadow_band", "ramps_soft",
                  [(0.0, (0.15, 0.15, 0.15)), (0.12, (0.55, 0.55, 0.55)), (0.35, (1.0, 1.0, 1.0))], "gritted",
                  blendingmode=MULTIPLY, opacitymult=0.6)
    g.bind("shadowed", "opacitymult", lerp(0.2, 0.9, get("row_depth")).graph())
    ao_darken(g, "basecolor", "shadowed", floor=0.2, opacitymult=0.5)

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_base", "histogram_range", {"input": "surface"}, range=0.12, position=0.75)
    g.bind("rough_base", "position", get("roughness").graph())
    g.add("roughness", "blend", {"source": "granules", "destination": "rough_base"},
          blendingmode=ADD_SUB, opacitymult=0.05)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "tile"

SAMPLE_RANGES = {
    "exposed.shingle_color": ((0.05, 0.05, 0.05), (0.55, 0.32, 0.28)),
    "exposed.color_variation": (0.1, 0.9),
    "exposed.row_depth": (0.25, 0.9),
    "exposed.gap_width": (0.0, 0.08),
    "exposed.grit": (0.1, 0.9),
    "exposed.roughness": (0.55, 0.95),
    # the shingle id is warped like the shingles, so both warps keep one value
    "ramps_warp.intensity": (0.03, 0.03),
    "id_warp.intensity": (0.03, 0.03),
    "ramps_chipped.opacitymult": (0.0, 0.12),
    "edge_noise.scale": (4.0, 12.0),
    "clouded.opacitymult": (0.2, 0.9),
    "normal_main.intensity": (2.5, 7.0),
    "normal_grit.intensity": (0.1, 0.8),
}


def _pin_layout():
    """Both brick generators keep one staggered grid in every sampled variant, so the shingle id
    stays aligned with the shingles and the rows with the ramps."""
    return {"bricks.offset": (0.5, 0.5), "shingle_id.offset": (0.5, 0.5),
            "bricks.mask_random": (0.0, 0.0), "shingle_id.mask_random": (0.0, 0.0),
            "shingle_id.interstice": ((0.0, 0.0), (0.0, 0.0)), "shingle_id.bevel": (0.0, 0.0),
            "bricks.bevel": (0.0, 0.05)}


SAMPLE_RANGES.update(_pin_layout())
