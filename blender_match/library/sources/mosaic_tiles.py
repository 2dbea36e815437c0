"""Mosaic tiles: small square glass or glazed ceramic mosaic tiles (about 2 cm) in cement grout.

Structure
- Layout: a Tile Generator of softly bevelled squares ("brick" shape, 12 x 12 across the sample,
  so about 2-2.5 cm tiles on a 30 cm sample) with the grout gap bound to the exposed grout width,
  and a flat twin with full luminance randomness (a per-tile random value, the "tile id").
- Tilt: hand-set mosaic tiles never sit flat. Four Tile Generators of "gradation" ramps (left,
  right, up and down, each with its own seed and full luminance randomness) are subtracted in
  pairs (averaged with an inverted twin), giving every tile a random slope in x and in y; added to
  the tile relief they make the flash catch each tile differently, and lift each tile by a random
  amount at one edge (so no separate per-tile offset is needed).
- Height: tile bevels + tilt + a faint glaze waviness (clouds), sandy grout (BnW Spots 3) low in
  the joints. Normal from the height (OpenGL) combined with a fine glass-ripple detail normal.
- Colour: the exposed tile colour; a Tile Generator Color gives each tile a random hue that is
  soft-lit over it (exposed colour variation), plus a per-tile lightness shift from the tile id;
  glaze darker on the bevels; speckled grout of the exposed brightness; occlusion in the joints.
- Roughness: glossy faces around the exposed roughness, rough grout. Metallic 0.

Exposed parameters
- ``tile_color`` (float3): the mean colour of the tiles (mosaics come in any palette).
- ``color_variation``: how much tiles differ in hue and lightness (the per-tile overlays' opacity).
- ``grout_brightness``: the grout's gray level.
- ``grout_width``: joint width (tile generator interstice, both axes).
- ``tilt``: how unevenly the tiles are set (slope ramps' weight in the height).
- ``glaze_roughness``: roughness of the tile faces (glass is very glossy, matte ceramic less).
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD,
    ADD_SUB,
    COPY,
    MAX,
    MULTIPLY,
    OUR_OCCLUSION,
    OVERLAY,
    SOFT_LIGHT,
    TILES_MAX,
    ao_darken,
    constant_map,
    gradient_over,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph

SQUARE, BRICK, GRADATION = 1, 8, 9
N = 12


def build() -> SbsGraph:
    g = SbsGraph("mosaic_tiles")
    g.expose("tile_color", (0.22, 0.48, 0.58), min=0.0, max=1.0)
    g.expose("color_variation", 0.5, min=0.0, max=1.0)
    g.expose("grout_brightness", 0.7, min=0.0, max=1.0)
    g.expose("grout_width", 0.09, min=0.02, max=0.25)
    g.expose("tilt", 0.4, min=0.0, max=1.0)
    g.expose("glaze_roughness", 0.1, min=0.02, max=0.6)

    # ---- layout ------------------------------------------------------------------------------
    g.add("tiles", "tile_generator", blending_mode=TILES_MAX, seed=81, x_amount=N, y_amount=N, pattern=BRICK,
          pattern_specific=0.12, interstice=(0.09, 0.09), luminance_random=0.0)
    g.bind("tiles", "interstice", vector(get("grout_width"), get("grout_width")).graph())
    g.add("tile_id", "tile_generator", blending_mode=TILES_MAX, seed=81, x_amount=N, y_amount=N, pattern=SQUARE,
          interstice=(0.0, 0.0), luminance_random=1.0)
    g.add("tile_mask", "histogram_scan", {"input_1": "tiles"}, position=0.9, contrast=0.75)

    # ---- tilt: a random slope per tile, in x and y ---------------------------------------------
    # each tile's ramp goes from 0 at its left (top) edge up to a random height; a second ramp of
    # another seed, inverted, is averaged in, so slopes of either sign appear around mid-gray
    for axis, rot, seeds in (("x", 0.0, (82, 83)), ("y", 0.25, (84, 85))):
        for k in (0, 1):
            g.add(f"ramp_{axis}{k}", "tile_generator", blending_mode=TILES_MAX, seed=seeds[k], x_amount=N, y_amount=N,
                  pattern=GRADATION, rotation=rot, interstice=(0.0, 0.0), luminance_random=1.0)
        g.add(f"ramp_{axis}1_inv", "invert_grayscale", {"source": f"ramp_{axis}1"})
        g.add(f"slope_{axis}", "blend", {"source": f"ramp_{axis}0", "destination": f"ramp_{axis}1_inv"},
              blendingmode=COPY, opacitymult=0.5)
    g.add("slopes", "blend", {"source": "slope_y", "destination": "slope_x"},
          blendingmode=COPY, opacitymult=0.5)
    g.add("tiles_low", "histogram_range", {"input": "tiles"}, range=0.7, position=0.5)
    g.add("tiles_tilted", "blend", {"source": "slopes", "destination": "tiles_low", "opacity": "tile_mask"},
          blendingmode=ADD_SUB, opacitymult=0.15)
    g.bind("tiles_tilted", "opacitymult", lerp(0.0, 0.8, get("tilt")).graph())

    # ---- height ------------------------------------------------------------------------------
    g.add("waves", "clouds_2", seed=86, scale=3.0)
    g.add("tiles_wavy", "blend", {"source": "waves", "destination": "tiles_tilted", "opacity": "tile_mask"},
          blendingmode=ADD_SUB, opacitymult=0.04)
    g.add("sand", "bnw_spots_3", seed=87, scale=12.0)
    g.add("grout_relief", "histogram_range", {"input": "sand"}, range=0.1, position=0.15)
    g.add("height_max", "blend", {"source": "grout_relief", "destination": "tiles_wavy"},
          blendingmode=MAX, opacitymult=1.0)
    g.add("height", "histogram_range", {"input": "height_max"}, range=1.0, position=0.5)

    g.add("normal_main", "normal", {"input1": "height"}, intensity=4.0, inversedy=True)
    g.add("ripples", "perlin_noise_1", seed=88, scale=24.0)
    g.add("normal_ripples", "normal", {"input1": "ripples"}, intensity=0.12, inversedy=True)
    g.add("normal", "normal_combine", {"input": "normal_main", "input_1": "normal_ripples"})
    g.add("ao", "ambient_occlusion_2", {"source": "height"}, height_depth=0.12, spreading=0.06,
          model=OUR_OCCLUSION)

    # ---- colour ------------------------------------------------------------------------------
    g.add("glaze_base", "uniform", outputcolor=(0.22, 0.48, 0.58, 1.0))
    g.bind("glaze_base", "outputcolor", vector(get("tile_color", 3), 1.0).graph())
    g.add("tile_hues", "tile_generator_color", blending_mode=TILES_MAX, seed=89, x_amount=N, y_amount=N, pattern=SQUARE,
          interstice=(0.0, 0.0), color_random=0.5, pattern_color=(0.5, 0.5, 0.5, 1.0),
          luminance_random=0.0)
    g.add("glaze_hued", "blend", {"source": "tile_hues", "destination": "glaze_base"},
          blendingmode=SOFT_LIGHT, opacitymult=0.5)
    g.bind("glaze_hued", "opacitymult", lerp(0.0, 1.0, get("color_variation")).graph())
    gradient_over(g, "glaze_varied", "tile_tones", "tile_id", [(0.0, (0.32, 0.32, 0.32)), (1.0, (0.70, 0.70, 0.70))],
                  "glaze_hued", blendingmode=SOFT_LIGHT, opacitymult=0.5)
    g.bind("glaze_varied", "opacitymult", lerp(0.1, 0.9, get("color_variation")).graph())
    gradient_over(g, "glaze_pooled", "bevel_tones", "tiles", [(0.0, (0.55, 0.55, 0.55)), (0.7, (1.0, 1.0, 1.0))],
                  "glaze_varied", blendingmode=MULTIPLY, opacitymult=0.5)

    g.add("grout_base", "uniform", outputcolor=(0.70, 0.68, 0.64, 1.0))
    g.bind("grout_base", "outputcolor",
           vector(get("grout_brightness"), get("grout_brightness") * 0.97,
                  get("grout_brightness") * 0.91, 1.0).graph())
    gradient_over(g, "grout_speckled", "sand_tones", "sand", [(0.0, (0.32, 0.32, 0.32)), (1.0, (0.64, 0.63, 0.60))],
                  "grout_base", blendingmode=OVERLAY, opacitymult=0.6)
    g.add("surface", "blend", {"source": "glaze_pooled", "destination": "grout_speckled", "opacity": "tile_mask"},
          blendingmode=COPY, opacitymult=1.0)
    ao_darken(g, "basecolor", "surface", floor=0.25, opacitymult=0.5)

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_glaze", "histogram_range", {"input": "waves"}, range=0.05, position=0.1)
    g.bind("rough_glaze", "position", get("glaze_roughness").graph())
    g.add("rough_grout", "histogram_range", {"input": "sand"}, range=0.1, position=0.88)
    g.add("rough_surface", "blend", {"source": "rough_glaze", "destination": "rough_grout", "opacity": "tile_mask"},
          blendingmode=COPY, opacitymult=1.0)
    g.add("roughness", "blend", {"source": "ripples", "destination": "rough_surface", "opacity": "tile_mask"},
          blendingmode=ADD, opacitymult=0.03)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "tile"

SAMPLE_RANGES = {
    "exposed.tile_color": ((0.03, 0.03, 0.03), (0.95, 0.95, 0.95)),
    "exposed.color_variation": (0.1, 0.9),
    "exposed.grout_brightness": (0.25, 0.9),
    "exposed.grout_width": (0.05, 0.16),
    "exposed.tilt": (0.1, 0.9),
    "exposed.glaze_roughness": (0.04, 0.4),
    "tiles.pattern_specific": (0.04, 0.25),
    "tile_hues.color_random": (0.2, 0.9),
    "tiles_wavy.opacitymult": (0.0, 0.1),
    "glaze_pooled.opacitymult": (0.2, 0.8),
    "normal_main.intensity": (2.5, 7.0),
    "normal_ripples.intensity": (0.05, 0.5),
}


def _pin_layout(nodes):
    """The layout of the tile generators stays a grid in every sampled variant: the tile mask, the
    tile id, the hue layer and the tilt ramps must stay aligned tile for tile."""
    fixed = {"offset": 0.0, "rotation_random": 0.0, "position_random": 0.0, "scale": 1.0,
             "scale_random": 0.0, "mask_random": 0.0, "softness": 0.0}
    out = {}
    for node in nodes:
        for p, v in fixed.items():
            out[f"{node}.{p}"] = (v, v)
        out[f"{node}.size_xy"] = ((1.0, 1.0), (1.0, 1.0))
        if node != "tiles":
            out[f"{node}.interstice"] = ((0.0, 0.0), (0.0, 0.0))
        if node.startswith("ramp_"):
            r = 0.25 if node.startswith("ramp_y") else 0.0
            out[f"{node}.rotation"] = (r, r)
        else:
            out[f"{node}.rotation"] = (0.0, 0.0)
    return out


SAMPLE_RANGES.update(_pin_layout(["tiles", "tile_id", "tile_hues", "ramp_x0", "ramp_x1", "ramp_y0", "ramp_y1"]))
