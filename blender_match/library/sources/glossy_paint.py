"""Material: glossy enamel or lacquer paint on a flat surface, with brush streaks, orange peel and a few dust specks.

Structure
- Brush streaks: fine and coarse horizontal streak noises plus white noise smeared by a
  directional blur (the bristle marks), gently warped by clouds so the strokes wander; their
  depth in the height is the exposed brush-streak amount (0 gives a sprayed finish).
- Orange peel: a dense Perlin noise over a broad cloud undulation, exposed separately: a sprayed
  lacquer has peel and no streaks, a brushed enamel the reverse.
- Height: streaks + peel; normal from it (the flash highlight is stretched and broken by it).
- Dust: sparse white-noise dots, slightly blurred, plus a few larger lint specks (a thresholded
  spot noise); they are light gray, rough, and sit a hair above the paint (exposed dust amount).
- Colour: the exposed paint colour, a touch darker where the paint pooled in the streak valleys
  and faintly mottled; dust mixed on top.
- Roughness: low around the exposed roughness, a little higher in soft smudges (a grunge map)
  and high on the dust. Metallic 0.

Exposed parameters
- ``paint_color`` (float3): the paint colour (any hue; default a saturated blue).
- ``brush_streaks``: depth of the brush marks.
- ``orange_peel``: strength of the orange-peel ripple.
- ``roughness``: mean roughness of the gloss.
- ``dust``: how many dust specks and lint bits lie on it.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD,
    ADD_SUB,
    DUST_COLOR,
    DUST_OPACITY,
    DUST_RELIEF,
    DUST_ROUGHNESS,
    MULTIPLY,
    OVERLAY,
    SOFT_LIGHT,
    color_over,
    constant_map,
    dust_specks,
    gradient_over,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("glossy_paint")
    g.expose("paint_color", (0.06, 0.20, 0.58), min=0.0, max=1.0)
    g.expose("brush_streaks", 0.5, min=0.0, max=1.0)
    g.expose("orange_peel", 0.3, min=0.0, max=1.0)
    g.expose("roughness", 0.07, min=0.02, max=0.5)
    g.expose("dust", 0.35, min=0.0, max=1.0)

    # ---- brush streaks -----------------------------------------------------------------------
    g.add("streak_fine", "anisotropic_noise", seed=71, x_amount=3, y_amount=200, smoothness=0.3)
    g.add("streak_coarse", "anisotropic_noise", seed=72, x_amount=2, y_amount=40, smoothness=0.8)
    g.add("bristle_noise", "white_noise", seed=73)
    g.add("bristles", "dirmotionblur", {"input1": "bristle_noise"}, intensity=24.0, mblurangle=0.0)
    g.add("bristles_level", "histogram_range", {"input": "bristles"}, range=1.0, position=0.5)
    g.add("streak_mix", "blend", {"source": "streak_coarse", "destination": "streak_fine"},
          blendingmode=OVERLAY, opacitymult=0.5)
    g.add("streak_all", "blend", {"source": "bristles_level", "destination": "streak_mix"},
          blendingmode=OVERLAY, opacitymult=0.4)
    g.add("wander", "clouds_2", seed=74, scale=2.0)
    g.add("wander_smooth", "perlin_noise", seed=79, scale=3.0)
    g.add("streaks", "warp", {"input1": "streak_all", "inputgradient": "wander_smooth"}, intensity=0.5)
    g.add("streak_height", "histogram_range", {"input": "streaks"}, range=0.3, position=0.5)
    g.bind("streak_height", "range", lerp(0.0, 0.6, get("brush_streaks")).graph())

    # ---- orange peel -------------------------------------------------------------------------
    g.add("peel", "perlin_noise", seed=75, scale=44.0)
    g.add("peel_undulated", "blend", {"source": "wander", "destination": "peel"},
          blendingmode=ADD_SUB, opacitymult=0.15)
    g.add("peel_height", "histogram_range", {"input": "peel_undulated"}, range=0.3, position=0.5)
    g.bind("peel_height", "range", lerp(0.0, 0.5, get("orange_peel")).graph())

    # ---- dust --------------------------------------------------------------------------------
    dust_specks(g, get("dust"), seeds=(76, 77))

    # ---- height and normal -------------------------------------------------------------------
    g.add("paint_relief", "blend", {"source": "peel_height", "destination": "streak_height"},
          blendingmode=ADD_SUB, opacitymult=1.0)
    g.add("height", "blend", {"source": "dust_mask", "destination": "paint_relief"},
          blendingmode=ADD, opacitymult=DUST_RELIEF)
    g.add("normal", "normal", {"input1": "height"}, intensity=1.2, inversedy=True)

    # ---- colour ------------------------------------------------------------------------------
    g.add("paint", "uniform", outputcolor=(0.06, 0.20, 0.58, 1.0))
    g.bind("paint", "outputcolor", vector(get("paint_color", 3), 1.0).graph())
    gradient_over(g, "paint_pooled", "pooling", "streak_height",
                  [(0.0, (0.86, 0.86, 0.86)), (0.5, (0.97, 0.97, 0.97)), (1.0, (1.0, 1.0, 1.0))], "paint",
                  blendingmode=MULTIPLY, opacitymult=0.8)
    gradient_over(g, "paint_mottled", "mottle", "wander", [(0.0, (0.45, 0.45, 0.45)), (1.0, (0.55, 0.55, 0.55))],
                  "paint_pooled", blendingmode=SOFT_LIGHT, opacitymult=0.5)
    color_over(g, "basecolor", "dust_color", DUST_COLOR, "paint_mottled", mask="dust_mask",
               opacitymult=DUST_OPACITY)

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("smudges_noise", "grunge_map_002", seed=78, scale=2.0)
    g.add("smudges", "histogram_scan", {"input_1": "smudges_noise"}, position=0.35, contrast=0.3)
    g.add("rough_base", "histogram_range", {"input": "streaks"}, range=0.04, position=0.12)
    g.bind("rough_base", "position", get("roughness").graph())
    g.add("rough_smudged", "blend", {"source": "smudges", "destination": "rough_base"},
          blendingmode=ADD, opacitymult=0.08)
    g.add("dust_rough", "uniform", colorswitch=False, outputcolor=DUST_ROUGHNESS)
    g.add("roughness", "blend", {"source": "dust_rough", "destination": "rough_smudged",
                                 "opacity": "dust_mask"})
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g)
    return g


FAMILY = "coating"

SAMPLE_RANGES = {
    "exposed.paint_color": ((0.02, 0.02, 0.02), (0.9, 0.9, 0.9)),
    "exposed.brush_streaks": (0.0, 0.9),
    "exposed.orange_peel": (0.0, 0.7),
    "exposed.roughness": (0.04, 0.3),
    "exposed.dust": (0.0, 0.8),
    "streak_mix.opacitymult": (0.2, 0.8),
    "streak_all.opacitymult": (0.1, 0.7),
    "streaks.intensity": (0.0, 1.0),
    "normal.intensity": (0.5, 2.5),
    "paint_pooled.opacitymult": (0.3, 1.0),
    "rough_smudged.opacitymult": (0.0, 0.2),
}
