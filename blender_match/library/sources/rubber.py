"""Rubber: a moulded rubber floor mat with raised coin dots and a fine matte grain, black by default.

Structure
- Pattern: a Tile Generator of discs (9 x 9 on a ~30 cm sample, so coins about 2 cm across on a
  3.3 cm pitch), diameter bound to the exposed dot size, softened by a blur so the moulded coins
  have rounded shoulders, then shaped by a histogram scan into flat tops.
- Grain: the moulded matte texture of the whole mat, white noise slightly blurred (BnW Spots 3 at
  its finest scale still gave crackle-like blotches at this sample size); its darkest texels are
  the pores where dust settles. A broad clouds undulation (the mat is never perfectly flat).
- Height: coins (exposed relief) + grain (exposed grain) + undulation. Normal from the height
  (OpenGL) combined with a fine grain detail normal; ambient occlusion around the coins.
- Colour: the exposed rubber colour, slightly lighter and grayer on the coin tops where feet rub
  and dust is trodden in, a pale dust film in the grain's pores and around the coin feet (exposed
  dust), faint mottling, occlusion.
- Roughness: matte around the exposed roughness, coin tops a little smoother (polished by wear),
  dust rougher. Metallic 0.

Exposed parameters
- ``rubber_color`` (float3): the rubber's colour (black, gray, or any dyed colour).
- ``dot_size``: coin diameter as a fraction of the pitch.
- ``relief``: how high the coins stand (histogram range of the coin layer).
- ``grain``: strength of the fine moulded grain.
- ``dust``: pale dust in the pores and around the coins, and wear on the coin tops.
- ``roughness``: the mat's mean roughness.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD,
    ADD_SUB,
    COPY,
    MULTIPLY,
    OUR_OCCLUSION,
    SCREEN,
    SOFT_LIGHT,
    SUBTRACT,
    TILES_MAX,
    ao_darken,
    constant_map,
    gradient_over,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph

DISC = 2
N = 9


def build() -> SbsGraph:
    g = SbsGraph("rubber")
    g.expose("rubber_color", (0.035, 0.035, 0.037), min=0.0, max=1.0)
    g.expose("dot_size", 0.6, min=0.2, max=0.9)
    g.expose("relief", 0.5, min=0.0, max=1.0)
    g.expose("grain", 0.5, min=0.0, max=1.0)
    g.expose("dust", 0.3, min=0.0, max=1.0)
    g.expose("roughness", 0.8, min=0.3, max=1.0)

    # ---- coins -------------------------------------------------------------------------------
    g.add("discs", "tile_generator", blending_mode=TILES_MAX, seed=71, x_amount=N, y_amount=N, pattern=DISC, scale=0.6,
          interstice=(0.0, 0.0), luminance_random=0.0)
    g.bind("discs", "scale", get("dot_size").graph())
    g.add("discs_soft", "blur_hq_grayscale", {"source": "discs"}, intensity=2.0)
    g.add("coins", "histogram_scan", {"input_1": "discs_soft"}, position=0.5, contrast=0.35)
    g.add("coin_tops", "histogram_scan", {"input_1": "coins"}, position=0.8, contrast=0.7)
    g.add("coins_spread", "blur_hq_grayscale", {"source": "coins"}, intensity=3.0)
    g.add("feet_ring", "blend", {"source": "coins", "destination": "coins_spread"},
          blendingmode=SUBTRACT, opacitymult=1.0)
    g.add("coin_feet", "histogram_scan", {"input_1": "feet_ring"}, position=0.88, contrast=0.6)

    # ---- grain and undulation ----------------------------------------------------------------
    g.add("fine", "white_noise")
    g.add("grain_soft", "blur", {"input1": "fine"}, intensity=0.5)
    g.add("pores", "histogram_scan", {"input_1": "fine"}, position=0.08, contrast=0.8)
    g.add("undulation", "clouds_1", seed=73, scale=2.0)

    # ---- height ------------------------------------------------------------------------------
    g.add("coin_level", "histogram_range", {"input": "coins"}, range=0.5, position=0.5)
    g.bind("coin_level", "range", lerp(0.05, 0.9, get("relief")).graph())
    g.add("grained", "blend", {"source": "grain_soft", "destination": "coin_level"},
          blendingmode=ADD_SUB, opacitymult=0.05)
    g.bind("grained", "opacitymult", lerp(0.0, 0.1, get("grain")).graph())
    g.add("undulated", "blend", {"source": "undulation", "destination": "grained"},
          blendingmode=ADD_SUB, opacitymult=0.05)
    g.add("height", "histogram_range", {"input": "undulated"}, range=1.0, position=0.5)

    g.add("normal_main", "normal", {"input1": "height"}, intensity=5.0, inversedy=True)
    g.add("normal_grain", "normal", {"input1": "grain_soft"}, intensity=0.5, inversedy=True)
    g.bind("normal_grain", "intensity", lerp(0.05, 1.0, get("grain")).graph())
    g.add("normal", "normal_combine", {"input": "normal_main", "input_1": "normal_grain"})
    g.add("ao", "ambient_occlusion_2", {"source": "height"}, height_depth=0.12, spreading=0.06,
          model=OUR_OCCLUSION)

    # ---- colour ------------------------------------------------------------------------------
    g.add("base", "uniform", outputcolor=(0.035, 0.035, 0.037, 1.0))
    g.bind("base", "outputcolor", vector(get("rubber_color", 3), 1.0).graph())
    gradient_over(g, "mottled", "mottle", "undulation", [(0.0, (0.42, 0.42, 0.42)), (1.0, (0.58, 0.58, 0.58))], "base",
                  blendingmode=SOFT_LIGHT, opacitymult=0.6)
    gradient_over(g, "grain_colored", "grain_tones", "grain_soft",
                  [(0.0, (0.40, 0.40, 0.40)), (1.0, (0.60, 0.60, 0.60))], "mottled", blendingmode=SOFT_LIGHT,
                  opacitymult=0.6)
    # dust: pale gray, trapped in pores and at the coin feet, rubbed onto the coin tops
    g.add("dust_color", "uniform", outputcolor=(0.42, 0.41, 0.39, 1.0))
    g.add("dust_places", "blend", {"source": "coin_feet", "destination": "pores"},
          blendingmode=SCREEN, opacitymult=0.7)
    g.add("dust_cover", "histogram_scan", {"input_1": "undulation"}, position=0.6, contrast=0.3)
    g.bind("dust_cover", "position", lerp(0.15, 1.0, get("dust")).graph())
    g.add("dust_mask", "blend", {"source": "dust_cover", "destination": "dust_places"},
          blendingmode=MULTIPLY, opacitymult=1.0)
    g.add("dusty", "blend", {"source": "dust_color", "destination": "grain_colored", "opacity": "dust_mask"},
          blendingmode=COPY, opacitymult=0.4)
    g.add("worn", "blend", {"source": "dust_color", "destination": "dusty", "opacity": "coin_tops"},
          blendingmode=SCREEN, opacitymult=0.1)
    g.bind("worn", "opacitymult", lerp(0.0, 0.25, get("dust")).graph())
    ao_darken(g, "basecolor", "worn", floor=0.3, opacitymult=0.5)

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_base", "histogram_range", {"input": "grain_soft"}, range=0.08, position=0.8)
    g.bind("rough_base", "position", get("roughness").graph())
    g.add("rough_tops", "blend", {"source": "coin_tops", "destination": "rough_base"},
          blendingmode=SUBTRACT, opacitymult=0.08)
    g.add("roughness", "blend", {"source": "dust_mask", "destination": "rough_tops"},
          blendingmode=ADD, opacitymult=0.15)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "coating"

SAMPLE_RANGES = {
    "exposed.rubber_color": ((0.02, 0.02, 0.02), (0.65, 0.65, 0.65)),
    "exposed.dot_size": (0.4, 0.8),
    "exposed.relief": (0.2, 0.9),
    "exposed.grain": (0.1, 0.9),
    "exposed.dust": (0.0, 0.7),
    "exposed.roughness": (0.6, 0.95),
    "discs_soft.intensity": (1.0, 3.5),
    "coins.contrast": (0.15, 0.6),
    "grain_soft.intensity": (0.2, 1.0),
    "mottled.opacitymult": (0.2, 0.9),
    "normal_main.intensity": (3.0, 8.0),
    # the coins stay on a square grid
    "discs.offset": (0.0, 0.0),
    "discs.position_random": (0.0, 0.0),
    "discs.rotation_random": (0.0, 0.0),
    "discs.scale_random": (0.0, 0.0),
    "discs.mask_random": (0.0, 0.0),
    "discs.size_xy": ((1.0, 1.0), (1.0, 1.0)),
    "discs.softness": (0.0, 0.0),
    "discs.interstice": ((0.0, 0.0), (0.0, 0.0)),
    "pores.position": (0.03, 0.12),
}
