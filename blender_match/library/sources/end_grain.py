"""Material: end-grain wood butcher block, glued blocks in a staggered grid showing growth-ring arcs and rays.

Structure
- Blocks: two Brick Generators with one layout (6 x 8 cells, rows offset by half a block): one with
  thin glue gaps and a tiny bevel (the glue lines), one flat with full luminance randomness (a
  per-block random value, the "block id").
- Growth rings: the distance to scattered feature points (Cells 2 at a low scale) stands for the
  distance to the pith of the log; a Perlin noise wobbles it (rings are never perfect circles) and
  five folds (|2x - 1|, from two histogram scans and a max blend each) turn it into a triangle
  wave of 16 periods; a gradient map gives each trough a thin dark latewood band fading into pale
  earlywood, so each pith shows as a set of concentric arcs.
- Radial rays: white noise smeared along the slope of that distance field (Slope Blur) gives short
  streaks that point away from the pith, thresholded into thin rays.
- Each block is a different slice of a different log: the ring field and the rays are shifted
  diagonally by the block id (Directional Warp; one warp, as a second one would shift the block
  edges of the first), so the arcs jump at every glue line.
- Pores: fine dark specks (a white-noise threshold) sunk into the surface.
- Colour: earlywood (the exposed colour) and a darker, warmer latewood through the ring mask,
  per-block tone shifts (exposed variation), clouds, pores and rays, dark glue lines.
- Height: latewood slightly proud (it is harder and wears less), pores and glue lines sunk; normal
  (OpenGL) from it; ambient occlusion from the height. Roughness: oiled end grain, matte around the
  exposed roughness, pores and glue lines rougher. Metallic 0.

Exposed parameters
- ``wood_color`` (float3): earlywood colour; latewood is a darker, warmer derivative.
- ``ring_density``: how many rings cross a block (range of the pith distance fed to the ring map).
- ``ring_contrast``: how much the latewood bands stand out.
- ``block_variation``: per-block colour differences (boards cut from different trees).
- ``roughness``: mean roughness of the oiled surface.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD,
    ADD_SUB,
    COPY,
    MULTIPLY,
    OVERLAY,
    SOFT_LIGHT,
    SUBTRACT,
    color_over,
    constant_map,
    fold,
    gradient_keys,
    gradient_over,
    keys_near,
    normal_and_ao,
    rgba_near,
    set_material_outputs,
)
from blender_match.library.expressions import const, get, lerp, vector
from blender_match.translator.runtime import SbsGraph

FOLDS = 5
# the ring profile over the folded distance (0 at a latewood line, 1 mid-earlywood)
RING_PROFILE = [(0.0, (0.0, 0.0, 0.0)), (0.1, (0.2, 0.2, 0.2)), (0.3, (0.85, 0.85, 0.85)),
                (1.0, (1.0, 1.0, 1.0))]


BLOCK_TONES = [(0.0, (0.26, 0.25, 0.25)), (0.3, (0.42, 0.41, 0.40)), (0.6, (0.55, 0.53, 0.50)),
               (1.0, (0.70, 0.66, 0.58))]
CLOUD_TONES = [(0.0, (0.44, 0.44, 0.44)), (1.0, (0.56, 0.55, 0.53))]
GLUE_COLOR = (0.45, 0.40, 0.36)
PORE_COLOR = (0.22, 0.15, 0.09)
RAY_COLOR = (0.62, 0.62, 0.62)


def build() -> SbsGraph:
    g = SbsGraph("end_grain")
    g.expose("wood_color", (0.72, 0.52, 0.33), min=0.0, max=1.0)
    g.expose("ring_density", 0.45, min=0.0, max=1.0)
    g.expose("ring_contrast", 0.6, min=0.0, max=1.0)
    g.expose("block_variation", 0.7, min=0.0, max=1.0)
    g.expose("roughness", 0.6, min=0.2, max=1.0)

    # ---- blocks ------------------------------------------------------------------------------
    layout = dict(x_amount=6, y_amount=8, offset=0.5)
    g.add("blocks", "brick_generator", seed=81, interstice=(0.015, 0.025), bevel=0.03,
          luminance_random=0.0, **layout)
    g.add("block_id", "brick_generator", seed=81, interstice=(0.0, 0.0), bevel=0.0,
          luminance_random=1.0, **layout)
    g.add("glue", "invert_grayscale", {"source": "blocks"})
    g.add("glue_line", "histogram_scan", {"input_1": "glue"}, position=0.1, contrast=0.6)

    # ---- growth rings ------------------------------------------------------------------------
    g.add("pith_dist", "cells_2", seed=83, scale=3, disorder=0.7)
    g.add("wobble", "perlin_noise_1", seed=84, scale=6.0)
    g.add("pith_wobbly", "blend", {"source": "wobble", "destination": "pith_dist"},
          blendingmode=ADD_SUB, opacitymult=0.04)
    g.add("pith_span", "histogram_range", {"input": "pith_wobbly"}, range=0.7, position=0.5)
    g.bind("pith_span", "range", lerp(0.35, 1.0, get("ring_density")).graph())
    g.add("field", "directionalwarp", {"input1": "pith_span", "inputintensity": "block_id"},
          intensity=64.0, warpangle=0.12)
    folded = "field"
    for i in range(FOLDS):
        folded = fold(g, folded, i)
    g.add("rings", "gradient", {"input1": folded}, colorswitch=False, **gradient_keys(RING_PROFILE))

    # ---- radial rays -------------------------------------------------------------------------
    g.add("ray_noise", "white_noise", seed=85)
    g.add("ray_streaks", "slope_blur_grayscale", {"source": "ray_noise", "effect": "pith_dist"},
          samples=4, mode=7, intensity=6.0)
    g.add("rays_raw", "histogram_scan", {"input_1": "ray_streaks"}, position=0.3, contrast=0.8)
    g.add("rays", "directionalwarp", {"input1": "rays_raw", "inputintensity": "block_id"},
          intensity=64.0, warpangle=0.12)

    # ---- pores -------------------------------------------------------------------------------
    g.add("pore_noise", "white_noise", seed=86)
    g.add("pores", "histogram_scan", {"input_1": "pore_noise"}, position=0.06, contrast=0.6)

    # ---- colour ------------------------------------------------------------------------------
    wood = get("wood_color", 3)
    g.add("earlywood", "uniform", outputcolor=(0.72, 0.52, 0.33, 1.0))
    g.bind("earlywood", "outputcolor", vector(wood, 1.0).graph())
    g.add("latewood", "uniform", outputcolor=(0.45, 0.25, 0.13, 1.0))
    g.bind("latewood", "outputcolor", vector(wood * const((0.62, 0.48, 0.38)), 1.0).graph())
    g.add("late_mask", "invert_grayscale", {"source": "rings"})
    g.add("ringed", "blend", {"source": "latewood", "destination": "earlywood", "opacity": "late_mask"},
          blendingmode=COPY, opacitymult=0.6)
    g.bind("ringed", "opacitymult", lerp(0.1, 1.0, get("ring_contrast")).graph())
    gradient_over(g, "blocks_varied", "block_tones", "block_id", BLOCK_TONES, "ringed", blendingmode=OVERLAY,
                  opacitymult=0.5)
    g.bind("blocks_varied", "opacitymult", get("block_variation").graph())
    g.add("clouds", "clouds_2", seed=87, scale=3.0)
    gradient_over(g, "clouded", "cloud_tones", "clouds", CLOUD_TONES, "blocks_varied", blendingmode=SOFT_LIGHT,
                  opacitymult=0.5)
    color_over(g, "rayed", "ray_color", (*RAY_COLOR, 1.0), "clouded", mask="rays", blendingmode=SOFT_LIGHT,
               opacitymult=0.5)
    color_over(g, "pored", "pore_color", (*PORE_COLOR, 1.0), "rayed", mask="pores", blendingmode=MULTIPLY,
               opacitymult=0.35)
    color_over(g, "basecolor", "glue_color", (*GLUE_COLOR, 1.0), "pored", mask="glue_line", blendingmode=MULTIPLY,
               opacitymult=0.8)

    # ---- height and normal -------------------------------------------------------------------
    g.add("h_rings", "histogram_range", {"input": "late_mask"}, range=0.12, position=0.6)
    g.add("h_pores", "blend", {"source": "pores", "destination": "h_rings"},
          blendingmode=SUBTRACT, opacitymult=0.15)
    g.add("h_glue", "blend", {"source": "glue_line", "destination": "h_pores"},
          blendingmode=SUBTRACT, opacitymult=0.3)
    g.add("height", "histogram_range", {"input": "h_glue"}, range=1.0, position=0.5)
    normal_and_ao(g, "height", intensity=2.0, height_depth=0.08, spreading=0.05)

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_base", "histogram_range", {"input": "clouds"}, range=0.1, position=0.6)
    g.bind("rough_base", "position", get("roughness").graph())
    g.add("rough_pores", "blend", {"source": "pores", "destination": "rough_base"},
          blendingmode=ADD, opacitymult=0.12)
    g.add("roughness", "blend", {"source": "glue_line", "destination": "rough_pores"},
          blendingmode=ADD, opacitymult=0.15)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "wood"

SAMPLE_RANGES = {
    "exposed.wood_color": ((0.55, 0.34, 0.16), (0.82, 0.50, 0.28)),
    "exposed.ring_density": (0.2, 1.0),
    "exposed.ring_contrast": (0.3, 1.0),
    "exposed.block_variation": (0.1, 1.0),
    "exposed.roughness": (0.4, 0.85),
    "pith_dist.disorder": (0.3, 1.0),
    "pith_wobbly.opacitymult": (0.01, 0.08),
    "field.warpangle": (0.08, 0.17),
    "rays_raw.position": (0.15, 0.45),
    "pores.position": (0.02, 0.1),
    "pored.opacitymult": (0.15, 0.5),
    "normal.intensity": (1.0, 4.0),
    "ray_streaks.intensity": (3.0, 10.0),
    "block_tones.colors": keys_near(BLOCK_TONES, 0.03),
    "cloud_tones.colors": keys_near(CLOUD_TONES, 0.03),
    "glue_color.outputcolor": rgba_near(GLUE_COLOR, 0.04),
    "pore_color.outputcolor": rgba_near(PORE_COLOR, 0.05),
    "ray_color.outputcolor": rgba_near(RAY_COLOR, 0.04),
    "rings.positions": ([0.0, 0.06, 0.22, 1.0], [0.0, 0.14, 0.38, 1.0]),
    # the folds are exact arithmetic (|2x - 1|): their scans and max blends stay pinned
    **{f"fold{i}_{side}.{param}": (value, value) for i in range(FOLDS) for side in ("hi", "lo")
       for param, value in (("position", 0.25), ("contrast", 0.0))},
    **{f"fold{i}.opacitymult": (1.0, 1.0) for i in range(FOLDS)},
}
