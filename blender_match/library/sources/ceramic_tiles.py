"""Ceramic tiles: glossy glazed square wall/floor tiles in a grid, with cement grout joints.

Structure
- Layout: a Tile Generator of bevelled squares ("brick" shape, 4 x 4) with a grout gap bound to
  the exposed grout width, and a flat twin with full luminance randomness (a per-tile random
  value, the "tile id").
- Height: the tiles' rounded bevels, a slight per-tile height offset (tiles never sit perfectly
  flat), a low glaze waviness (clouds) on the faces, and sandy grout (BnW Spots 3) low in the
  joints. Normal from the height (OpenGL) combined with a faint glaze-ripple detail normal.
- Colour: the exposed tile colour with a small per-tile variation (soft light of a gradient of the
  tile id), glaze pooling that darkens the bevels slightly,
  speckled grout of the exposed brightness, grime collecting in the joints (dirt noise, exposed
  dirt), and occlusion.
- Roughness: glossy glaze around the exposed roughness with faint clouds variation, grime
  raising it, rough grout. Metallic 0.

Exposed parameters
- ``tile_color`` (float3): the glaze colour.
- ``grout_brightness``: the grout's gray level.
- ``grout_width``: joint width (tile generator interstice, both axes).
- ``glaze_roughness``: roughness of the tile faces.
- ``dirt``: grime in the joints and on the tiles (mask threshold, roughness increase).
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
    color_over,
    constant_map,
    gradient_over,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph

SQUARE, BRICK = 1, 8


def build() -> SbsGraph:
    g = SbsGraph("ceramic_tiles")
    g.expose("tile_color", (0.78, 0.80, 0.78), min=0.0, max=1.0)
    g.expose("grout_brightness", 0.62, min=0.0, max=1.0)
    g.expose("grout_width", 0.035, min=0.005, max=0.12)
    g.expose("glaze_roughness", 0.16, min=0.03, max=0.6)
    g.expose("dirt", 0.3, min=0.0, max=1.0)

    # ---- layout ------------------------------------------------------------------------------
    g.add("tiles", "tile_generator", blending_mode=TILES_MAX, seed=31, x_amount=4, y_amount=4, pattern=BRICK,
          pattern_specific=0.08, interstice=(0.035, 0.035), luminance_random=0.0)
    g.bind("tiles", "interstice", vector(get("grout_width"), get("grout_width")).graph())
    g.add("tile_id", "tile_generator", blending_mode=TILES_MAX, seed=31, x_amount=4, y_amount=4, pattern=SQUARE,
          interstice=(0.0, 0.0), luminance_random=1.0)
    g.add("tiles_round", "blur_hq_grayscale", {"source": "tiles"}, intensity=1.2)
    g.add("tile_mask", "histogram_scan", {"input_1": "tiles_round"}, position=0.9, contrast=0.7)

    # ---- height ------------------------------------------------------------------------------
    g.add("tilt", "histogram_range", {"input": "tile_id"}, range=0.06, position=0.94)
    g.add("tiles_tilted", "blend", {"source": "tilt", "destination": "tiles_round"},
          blendingmode=MULTIPLY, opacitymult=1.0)
    g.add("glaze_waves", "clouds_2", seed=32, scale=4.0)
    g.add("tiles_glazed", "blend", {"source": "glaze_waves", "destination": "tiles_tilted", "opacity": "tile_mask"},
          blendingmode=ADD_SUB, opacitymult=0.04)
    g.add("sand", "bnw_spots_3", seed=33, scale=10.0)
    g.add("grout_relief", "histogram_range", {"input": "sand"}, range=0.12, position=0.18)
    g.add("height_max", "blend", {"source": "grout_relief", "destination": "tiles_glazed"},
          blendingmode=MAX, opacitymult=1.0)
    g.add("height", "histogram_range", {"input": "height_max"}, range=1.0, position=0.5)

    g.add("normal_main", "normal", {"input1": "height"}, intensity=5.0, inversedy=True)
    g.add("ripples", "perlin_noise_1", seed=34, scale=12.0)
    g.add("ripples_masked", "blend", {"source": "ripples", "destination": "tile_mask", "opacity": "tile_mask"},
          blendingmode=MULTIPLY, opacitymult=1.0)
    g.add("normal_ripples", "normal", {"input1": "ripples_masked"}, intensity=0.25, inversedy=True)
    g.add("normal", "normal_combine", {"input": "normal_main", "input_1": "normal_ripples"})
    g.add("ao", "ambient_occlusion_2", {"source": "height"}, height_depth=0.1, spreading=0.08,
          model=OUR_OCCLUSION)

    # ---- colour ------------------------------------------------------------------------------
    g.add("glaze_base", "uniform", outputcolor=(0.78, 0.80, 0.78, 1.0))
    g.bind("glaze_base", "outputcolor", vector(get("tile_color", 3), 1.0).graph())
    gradient_over(g, "glaze_varied", "tile_tones", "tile_id", [(0.0, (0.44, 0.44, 0.45)), (1.0, (0.57, 0.56, 0.54))],
                  "glaze_base", blendingmode=SOFT_LIGHT, opacitymult=0.8)
    # glaze pools thicker (darker) along the bevels
    gradient_over(g, "glaze_pooled", "bevel_tones", "tiles_round",
                  [(0.0, (0.55, 0.55, 0.55)), (0.5, (0.72, 0.72, 0.74)), (1.0, (1.0, 1.0, 1.0))], "glaze_varied",
                  blendingmode=MULTIPLY, opacitymult=0.4)

    g.add("grout_base", "uniform", outputcolor=(0.62, 0.60, 0.56, 1.0))
    g.bind("grout_base", "outputcolor",
           vector(get("grout_brightness"), get("grout_brightness") * 0.97,
                  get("grout_brightness") * 0.9, 1.0).graph())
    gradient_over(g, "grout_speckled", "sand_tones", "sand", [(0.0, (0.34, 0.34, 0.34)), (1.0, (0.62, 0.61, 0.58))],
                  "grout_base", blendingmode=OVERLAY, opacitymult=0.6)
    g.add("surface", "blend", {"source": "glaze_pooled", "destination": "grout_speckled", "opacity": "tile_mask"},
          blendingmode=COPY, opacitymult=1.0)

    # grime: in the joints (grunge), and a light film on the tiles (soft clouds)
    g.add("dirt_noise", "grunge_map_001", seed=35, scale=2.0, balance=0.5, contrast=0.5)
    g.add("grout_mask", "invert_grayscale", {"source": "tile_mask"})
    g.add("grime_mask", "blend", {"source": "dirt_noise", "destination": "grout_mask"},
          blendingmode=MULTIPLY, opacitymult=1.0)
    g.add("grime_level", "histogram_scan", {"input_1": "grime_mask"}, position=0.35, contrast=0.1)
    g.bind("grime_level", "position", lerp(0.0, 0.8, get("dirt")).graph())
    color_over(g, "grimy", "grime_color", (0.22, 0.19, 0.15, 1.0), "surface", mask="grime_level", blendingmode=COPY,
               opacitymult=0.55)
    g.add("film", "histogram_scan", {"input_1": "glaze_waves"}, position=0.2, contrast=0.0)
    g.bind("film", "position", lerp(0.0, 0.6, get("dirt")).graph())
    g.add("filmy", "blend", {"source": "grime_color", "destination": "grimy", "opacity": "film"},
          blendingmode=MULTIPLY, opacitymult=0.07)
    ao_darken(g, "basecolor", "filmy", floor=0.25, opacitymult=0.5)

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_glaze", "histogram_range", {"input": "glaze_waves"}, range=0.06, position=0.16)
    g.bind("rough_glaze", "position", get("glaze_roughness").graph())
    g.add("rough_filmed", "blend", {"source": "film", "destination": "rough_glaze"},
          blendingmode=ADD, opacitymult=0.15)
    g.add("rough_grout", "histogram_range", {"input": "sand"}, range=0.1, position=0.9)
    g.add("rough_surface", "blend", {"source": "rough_filmed", "destination": "rough_grout", "opacity": "tile_mask"},
          blendingmode=COPY, opacitymult=1.0)
    g.add("roughness", "blend", {"source": "grime_level", "destination": "rough_surface"},
          blendingmode=MAX, opacitymult=0.9)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "tile"

SAMPLE_RANGES = {
    "exposed.tile_color": ((0.55, 0.58, 0.58), (0.92, 0.92, 0.90)),
    "exposed.grout_brightness": (0.3, 0.85),
    "exposed.grout_width": (0.015, 0.07),
    "exposed.glaze_roughness": (0.06, 0.35),
    "exposed.dirt": (0.0, 0.7),
    "tiles.pattern_specific": (0.02, 0.2),
    "tiles_glazed.opacitymult": (0.0, 0.1),
    "glaze_pooled.opacitymult": (0.2, 0.9),
    "glaze_varied.opacitymult": (0.3, 1.0),
    "normal_main.intensity": (3.0, 8.0),
    "normal_ripples.intensity": (0.05, 0.6),
}
