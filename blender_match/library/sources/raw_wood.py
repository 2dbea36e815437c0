"""Raw wood: an unfinished, rough-sawn softwood board (pine/spruce) with knots and saw marks.

Structure
- Grain: vertical wavy growth lines (Wood Fibers 2) sharpened by a histogram scan into thin
  latewood lines, plus fine vertical fibres (Wood Fibers 1).
- Knots: a few random blobs (Tile Generator of gaussians with position/scale randomness and a
  mask) whose gradient warps the grain so the lines flow around them; their cores are thresholded
  into dark knots, ringed by a darker halo.
- Saw marks: faint horizontal bands (Stripes, softened) across the board, in the height and
  slightly in the colour; a fibrous Anisotropic Noise, turned a quarter turn, for raised fibres.
- Colour: latewood lines between a pale earlywood and a darker latewood tone, both from the
  exposed wood colour; knots dark red-brown; clouds variation; weathering greys the wood in soft
  patches streaked along the fibres (exposed).
- Height: the grain lines slightly raised (rough-sawn), saw marks, knots proud, fibres; normal
  (OpenGL) from it combined with a fibre detail normal. Roughness: matte, raised fibres and
  weathering rougher, knots (resinous) a little smoother. Metallic 0.

Exposed parameters
- ``wood_color`` (float3): earlywood colour; the latewood is a darker, warmer derivative.
- ``ring_contrast``: how much the latewood lines stand out (opacity of the line colour).
- ``knots``: how many knots appear (tile mask randomness).
- ``weathering``: grey, sun-bleached, rougher patches (threshold of clouds x fibres).
- ``roughness``: mean roughness.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD,
    ADD_SUB,
    COPY,
    MULTIPLY,
    SOFT_LIGHT,
    SUBTRACT,
    TILES_MAX,
    color_over,
    constant_map,
    gradient_over,
    set_material_outputs,
)
from blender_match.library.expressions import const, get, lerp, vector
from blender_match.translator.runtime import SbsGraph

GAUSSIAN = 5


def build() -> SbsGraph:
    g = SbsGraph("raw_wood")
    g.expose("wood_color", (0.74, 0.58, 0.40), min=0.0, max=1.0)
    g.expose("ring_contrast", 0.6, min=0.0, max=1.0)
    g.expose("knots", 0.5, min=0.0, max=1.0)
    g.expose("weathering", 0.2, min=0.0, max=1.0)
    g.expose("roughness", 0.7, min=0.3, max=1.0)

    # ---- knots -------------------------------------------------------------------------------
    g.add("knot_blobs", "tile_generator", blending_mode=TILES_MAX, seed=61, x_amount=2, y_amount=3, pattern=GAUSSIAN,
          scale=0.55, position_random=0.4, scale_random=0.5, mask_random=0.5, offset=0.5)
    g.bind("knot_blobs", "mask_random", lerp(1.0, 0.0, get("knots")).graph())
    g.add("knot_field", "blur_hq_grayscale", {"source": "knot_blobs"}, intensity=8.0)

    # ---- grain -------------------------------------------------------------------------------
    g.add("rings_src", "wood_fibers_2", seed=62, scale=3.0, disorder=0.3)
    g.add("rings_warp", "warp", {"input1": "rings_src", "inputgradient": "knot_field"}, intensity=0.8)
    g.add("rings", "histogram_scan", {"input_1": "rings_warp"}, position=0.35, contrast=0.7)
    g.add("fibres", "wood_fibers_1", seed=63, scale=8.0, disorder=0.4)
    g.add("fibres_warp", "warp", {"input1": "fibres", "inputgradient": "knot_field"}, intensity=0.8)
    g.add("knot_core", "histogram_scan", {"input_1": "knot_blobs"}, position=0.2, contrast=0.75)
    g.add("knot_halo", "histogram_scan", {"input_1": "knot_field"}, position=0.35, contrast=0.2)

    # ---- saw marks and raised fibres ---------------------------------------------------------
    g.add("saw", "stripes", number=36, width=0.5, softness=1.0)
    g.add("saw_turn", "transformation", {"input1": "saw"}, matrix22=(0.0, 1.0, -1.0, 0.0))
    g.add("raised_src", "anisotropic_noise", seed=64, x_amount=16, y_amount=256, smoothness=0.2)
    g.add("raised", "transformation", {"input1": "raised_src"}, matrix22=(0.0, 1.0, -1.0, 0.0))

    # ---- height and normal -------------------------------------------------------------------
    g.add("h_base", "histogram_range", {"input": "rings"}, range=0.25, position=0.55)
    g.add("h_fibres", "blend", {"source": "fibres_warp", "destination": "h_base"},
          blendingmode=ADD_SUB, opacitymult=0.12)
    g.add("h_saw", "blend", {"source": "saw_turn", "destination": "h_fibres"},
          blendingmode=ADD_SUB, opacitymult=0.035)
    g.add("h_knots", "blend", {"source": "knot_core", "destination": "h_saw"},
          blendingmode=ADD, opacitymult=0.15)
    g.add("height", "histogram_range", {"input": "h_knots"}, range=1.0, position=0.5)
    g.add("normal_main", "normal", {"input1": "height"}, intensity=4.0, inversedy=True)
    g.add("normal_raised", "normal", {"input1": "raised"}, intensity=0.5, inversedy=True)
    g.add("normal", "normal_combine", {"input": "normal_main", "input_1": "normal_raised"})

    # ---- colour ------------------------------------------------------------------------------
    wood = get("wood_color", 3)
    g.add("earlywood", "uniform", outputcolor=(0.74, 0.58, 0.40, 1.0))
    g.bind("earlywood", "outputcolor", vector(wood, 1.0).graph())
    g.add("latewood", "uniform", outputcolor=(0.52, 0.33, 0.18, 1.0))
    g.bind("latewood", "outputcolor", vector(wood * const((0.72, 0.58, 0.45)), 1.0).graph())
    g.add("grain_color", "blend", {"source": "latewood", "destination": "earlywood", "opacity": "rings"},
          blendingmode=COPY, opacitymult=0.6)
    g.bind("grain_color", "opacitymult", get("ring_contrast").graph())
    gradient_over(g, "fibred", "fibre_tone", "fibres_warp", [(0.0, (0.44, 0.43, 0.42)), (1.0, (0.56, 0.55, 0.53))],
                  "grain_color", blendingmode=SOFT_LIGHT, opacitymult=0.7)
    g.add("clouds", "clouds_1", seed=65, scale=3.0)
    gradient_over(g, "clouded", "cloud_tone", "clouds", [(0.0, (0.42, 0.41, 0.40)), (1.0, (0.58, 0.56, 0.52))],
                  "fibred", blendingmode=SOFT_LIGHT, opacitymult=0.6)
    color_over(g, "haloed", "halo_color", (0.55, 0.36, 0.20, 1.0), "clouded", mask="knot_halo", blendingmode=MULTIPLY,
               opacitymult=0.35)
    color_over(g, "knotted", "knot_color", (0.30, 0.15, 0.07, 1.0), "haloed", mask="knot_core", blendingmode=COPY,
               opacitymult=0.9)
    gradient_over(g, "sawn", "saw_tone", "saw_turn", [(0.0, (0.46, 0.46, 0.46)), (1.0, (0.54, 0.54, 0.54))], "knotted",
                  blendingmode=SOFT_LIGHT, opacitymult=0.3)
    g.add("weather_streaks", "blend", {"source": "fibres_warp", "destination": "clouds"},
          blendingmode=MULTIPLY, opacitymult=0.6)
    g.add("weather_mask", "histogram_scan", {"input_1": "weather_streaks"}, position=0.2, contrast=0.3)
    g.bind("weather_mask", "position", lerp(0.0, 0.8, get("weathering")).graph())
    color_over(g, "basecolor", "weather_color", (0.52, 0.50, 0.47, 1.0), "sawn", mask="weather_mask", blendingmode=COPY,
               opacitymult=0.75)

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_base", "histogram_range", {"input": "raised"}, range=0.12, position=0.7)
    g.bind("rough_base", "position", get("roughness").graph())
    g.add("rough_weather", "blend", {"source": "weather_mask", "destination": "rough_base"},
          blendingmode=ADD, opacitymult=0.15)
    g.add("roughness", "blend", {"source": "knot_core", "destination": "rough_weather"},
          blendingmode=SUBTRACT, opacitymult=0.15)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g)
    return g


FAMILY = "wood"

SAMPLE_RANGES = {
    "exposed.wood_color": ((0.62, 0.44, 0.26), (0.86, 0.62, 0.40)),
    "exposed.ring_contrast": (0.3, 0.9),
    "exposed.knots": (0.0, 1.0),
    "exposed.weathering": (0.0, 0.7),
    "exposed.roughness": (0.55, 0.9),
    "rings_src.scale": (2.0, 6.0),
    "rings.position": (0.25, 0.5),
    "rings_warp.intensity": (0.3, 1.5),
    "fibred.opacitymult": (0.3, 1.0),
    "clouded.opacitymult": (0.2, 0.9),
    "normal_main.intensity": (2.0, 7.0),
}
