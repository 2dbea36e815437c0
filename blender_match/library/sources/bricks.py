"""Bricks: a running-bond wall of fired clay bricks with recessed, sandy mortar joints.

Structure
- Layout: two Brick Generators with one seed (4 x 12 cells, about 3:1 bricks, half offset): one
  bevelled with mortar gaps (the brick relief), one flat with full luminance randomness (a per-brick
  random value, the "brick id").
- Shape: the relief is warped by a fractal noise so the edges are not ruler-straight, then a
  spotty noise is subtracted from it and a histogram scan re-thresholds the result: the brick
  edges, where the bevel is low, get chipped (the exposed wear drives the subtraction).
- Surface: pits and sandy grain (BnW Spots 3) sink into the brick faces; the mortar has its own
  fine sandy relief at a lower level.
- Colour: a per-brick gradient (hue and value shifts around neutral: orange, red, purple-brown,
  a few burnt ones) is soft-lit over the exposed brick colour, with speckles and clouds; mortar
  colour (exposed brightness) in the joints; occlusion darkens the joints.
- Normal from the height (OpenGL) combined with a sandy detail normal. Roughness high and nearly
  uniform (mortar rougher), centred on the exposed roughness. Metallic 0.

Exposed parameters
- ``brick_color`` (float3): the average brick colour.
- ``brick_variation``: per-brick colour variation (opacity of the per-brick overlay).
- ``mortar_brightness``: the mortar's gray level (its colour node).
- ``wear``: chipped edges and pitted faces (noise subtraction depth, pit depth).
- ``roughness``: the bricks' mean roughness.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD_SUB,
    COPY,
    MAX,
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


def build() -> SbsGraph:
    g = SbsGraph("bricks")
    g.expose("brick_color", (0.50, 0.23, 0.15), min=0.0, max=1.0)
    g.expose("brick_variation", 0.6, min=0.0, max=1.0)
    g.expose("mortar_brightness", 0.55, min=0.0, max=1.0)
    g.expose("wear", 0.35, min=0.0, max=1.0)
    g.expose("roughness", 0.82, min=0.3, max=1.0)

    # ---- layout ------------------------------------------------------------------------------
    g.add("bricks", "brick_generator", seed=21, x_amount=4, y_amount=12, offset=0.5,
          interstice=(0.025, 0.09), bevel=0.18, luminance_random=0.0)
    g.add("brick_id", "brick_generator", seed=21, x_amount=4, y_amount=12, offset=0.5,
          interstice=(0.0, 0.0), bevel=0.0, luminance_random=1.0)
    g.add("edge_noise", "fractal_sum_1", seed=22, scale=6.0, roughness=0.55)
    g.add("bricks_warp", "warp", {"input1": "bricks", "inputgradient": "edge_noise"}, intensity=0.08)

    # chipped edges: noise eats the low (bevelled) border, then re-threshold
    g.add("chips_noise", "bnw_spots_1", seed=23, scale=6.0)
    g.add("bricks_eaten", "blend", {"source": "chips_noise", "destination": "bricks_warp"},
          blendingmode=SUBTRACT, opacitymult=0.35)
    g.bind("bricks_eaten", "opacitymult", lerp(0.02, 0.4, get("wear")).graph())
    g.add("brick_shape", "histogram_scan", {"input_1": "bricks_eaten"}, position=0.8, contrast=0.55)
    g.add("brick_soft", "blur_hq_grayscale", {"source": "brick_shape"}, intensity=1.0)

    # ---- surface relief ----------------------------------------------------------------------
    g.add("sand", "bnw_spots_3", seed=24, scale=8.0)
    g.add("pits", "histogram_scan", {"input_1": "sand"}, position=0.25, contrast=0.6, invert_position=True)
    g.add("brick_pitted", "blend", {"source": "pits", "destination": "brick_soft"},
          blendingmode=SUBTRACT, opacitymult=0.12)
    g.bind("brick_pitted", "opacitymult", lerp(0.04, 0.25, get("wear")).graph())
    g.add("clouds", "clouds_1", seed=25, scale=3.0)
    g.add("brick_bumpy", "blend", {"source": "clouds", "destination": "brick_pitted", "opacity": "brick_soft"},
          blendingmode=ADD_SUB, opacitymult=0.12)
    g.add("mortar_relief", "histogram_range", {"input": "sand"}, range=0.15, position=0.2)
    g.add("height_max", "blend", {"source": "mortar_relief", "destination": "brick_bumpy"},
          blendingmode=MAX, opacitymult=1.0)
    g.add("height", "histogram_range", {"input": "height_max"}, range=1.0, position=0.5)

    g.add("normal_main", "normal", {"input1": "height"}, intensity=5.0, inversedy=True)
    g.add("normal_sand", "normal", {"input1": "sand"}, intensity=0.8, inversedy=True)
    g.add("normal", "normal_combine", {"input": "normal_main", "input_1": "normal_sand"})
    g.add("ao", "ambient_occlusion_2", {"source": "height"}, height_depth=0.1, spreading=0.1,
          model=OUR_OCCLUSION)

    # ---- colour ------------------------------------------------------------------------------
    g.add("brick_base", "uniform", outputcolor=(0.50, 0.23, 0.15, 1.0))
    g.bind("brick_base", "outputcolor", vector(get("brick_color", 3), 1.0).graph())
    gradient_over(g, "brick_varied", "brick_tones", "brick_id", [
        (0.0, (0.22, 0.19, 0.20)), (0.2, (0.40, 0.34, 0.36)), (0.45, (0.50, 0.47, 0.45)),
        (0.75, (0.60, 0.52, 0.42)), (1.0, (0.70, 0.58, 0.44))], "brick_base", blendingmode=SOFT_LIGHT, opacitymult=0.6)
    g.bind("brick_varied", "opacitymult", get("brick_variation").graph())
    gradient_over(g, "brick_clouded", "cloud_tones", "clouds", [(0.0, (0.40, 0.40, 0.42)), (1.0, (0.60, 0.56, 0.50))],
                  "brick_varied", blendingmode=SOFT_LIGHT, opacitymult=0.7)
    gradient_over(g, "brick_speckled", "speckle_tones", "sand",
                  [(0.0, (0.30, 0.28, 0.27)), (0.5, (0.5, 0.5, 0.5)), (1.0, (0.62, 0.58, 0.52))], "brick_clouded",
                  blendingmode=OVERLAY, opacitymult=0.35)

    g.add("mortar_base", "uniform", outputcolor=(0.55, 0.53, 0.49, 1.0))
    g.bind("mortar_base", "outputcolor",
           vector(get("mortar_brightness") * 1.0, get("mortar_brightness") * 0.96,
                  get("mortar_brightness") * 0.88, 1.0).graph())
    g.add("mortar_speckled", "blend", {"source": "speckle_tones", "destination": "mortar_base"},
          blendingmode=OVERLAY, opacitymult=0.5)
    g.add("brick_mask", "histogram_scan", {"input_1": "brick_soft"}, position=0.85, contrast=0.6)
    g.add("wall", "blend", {"source": "brick_speckled", "destination": "mortar_speckled",
                            "opacity": "brick_mask"}, blendingmode=COPY, opacitymult=1.0)
    ao_darken(g, "basecolor", "wall", floor=0.15, opacitymult=0.45)

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_brick", "histogram_range", {"input": "sand"}, range=0.1, position=0.82)
    g.bind("rough_brick", "position", get("roughness").graph())
    g.add("rough_mortar", "uniform", colorswitch=False, outputcolor=(0.95, 0.95, 0.95, 1.0))
    g.add("roughness", "blend", {"source": "rough_brick", "destination": "rough_mortar", "opacity": "brick_mask"},
          blendingmode=COPY, opacitymult=1.0)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "tile"

SAMPLE_RANGES = {
    "exposed.brick_color": ((0.38, 0.15, 0.09), (0.66, 0.36, 0.24)),
    "exposed.brick_variation": (0.3, 1.0),
    "exposed.mortar_brightness": (0.3, 0.8),
    "exposed.wear": (0.0, 0.8),
    "exposed.roughness": (0.7, 0.95),
    "bricks.bevel": (0.08, 0.3),
    "bricks.interstice": ((0.015, 0.06), (0.04, 0.14)),
    "bricks_warp.intensity": (0.02, 0.16),
    "clouds.scale": (2.0, 6.0),
    "brick_clouded.opacitymult": (0.3, 1.0),
    "brick_speckled.opacitymult": (0.1, 0.6),
    "normal_main.intensity": (3.0, 9.0),
}
