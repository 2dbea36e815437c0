"""Carpet: dense cut-pile carpet or rug seen from above, packed fuzzy tufts, any colour.

Structure
- Tufts: the cut ends of the yarn bundles, rounded paraboloid bumps packed edge to edge by a Tile
  Sampler (about 32 tufts across a 30 cm sample, i.e. tufts of 8-10 mm; the exposed tuft size
  sets the count), jittered and varied in size and luminance (each tuft is its own yarn bundle); a
  second, finer and offset sampler fills the gaps so no floor shows between them, as in a dense
  pile.
- Fibres: the yarn ends are fuzzy, a curly fibre noise (Fur 1) and a fine white-noise speckle
  multiplied into the tufts (exposed fuzz), so the tuft outlines break up into fibres.
- Pile shading: a broad cloud that slightly lifts or sinks the pile (the shading of a carpet brushed
  in different directions).
- Height: tufts x fibres + shading; normal from it (OpenGL); strong ambient occlusion between the
  tufts (the pile is deep).
- Colour: the exposed carpet colour, per-tuft and per-fibre lightness variation (heathered yarn,
  exposed colour variation), darker deep in the pile (occlusion and the gradient of the height), a
  little lighter on the tuft tips.
- Roughness: fully matte (textile), a touch less on the tips. Metallic 0.

Exposed parameters
- ``carpet_color`` (float3): the yarn colour (any colour).
- ``color_variation``: per-tuft and heather lightness variation of the yarn.
- ``tuft_size``: size of the tufts (0 fine, dense pile; 1 coarse, shaggy).
- ``fuzz``: fibre fuzz breaking up the tufts.
- ``pile_depth``: how deep the gaps between tufts look (normal strength and gap darkening).
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD_SUB,
    MAX,
    MULTIPLY,
    SOFT_LIGHT,
    ao_darken,
    constant_map,
    gradient_over,
    normal_and_ao,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("carpet")
    g.expose("carpet_color", (0.42, 0.36, 0.30), min=0.0, max=1.0)
    g.expose("color_variation", 0.4, min=0.0, max=1.0)
    g.expose("tuft_size", 0.5, min=0.0, max=1.0)
    g.expose("fuzz", 0.5, min=0.0, max=1.0)
    g.expose("pile_depth", 0.5, min=0.0, max=1.0)
    size = get("tuft_size")

    # ---- tufts -------------------------------------------------------------------------------
    g.add("tufts_a", "tile_sampler", seed=81, x_amount=32, y_amount=32, pattern=3, scale=2.0,
          position_random=0.3, scale_random=0.3, luminance_random=0.4)
    g.bind("tufts_a", "x_amount", lerp(48.0, 20.0, size).graph())
    g.bind("tufts_a", "y_amount", lerp(48.0, 20.0, size).graph())
    g.add("tufts_b", "tile_sampler", seed=82, x_amount=40, y_amount=40, pattern=3, scale=1.8,
          position_random=0.4, scale_random=0.3, luminance_random=0.4, offset=0.5)
    g.bind("tufts_b", "x_amount", lerp(60.0, 25.0, size).graph())
    g.bind("tufts_b", "y_amount", lerp(60.0, 25.0, size).graph())
    g.add("tufts", "blend", {"source": "tufts_b", "destination": "tufts_a"},
          blendingmode=MAX, opacitymult=0.85)

    # ---- fibres ------------------------------------------------------------------------------
    g.add("curls", "fur_1", seed=83, scale=6.0)
    g.add("speckle", "white_noise", seed=84)
    g.add("fibres", "blend", {"source": "speckle", "destination": "curls"},
          blendingmode=SOFT_LIGHT, opacitymult=0.6)
    g.add("fibre_level", "histogram_range", {"input": "fibres"}, range=0.6, position=0.6)
    g.add("fuzzed", "blend", {"source": "fibre_level", "destination": "tufts"},
          blendingmode=MULTIPLY, opacitymult=0.5)
    g.bind("fuzzed", "opacitymult", lerp(0.1, 0.9, get("fuzz")).graph())

    # ---- pile shading and height -------------------------------------------------------------
    g.add("shading", "clouds_2", seed=85, scale=2.0)
    g.add("shaded", "blend", {"source": "shading", "destination": "fuzzed"},
          blendingmode=ADD_SUB, opacitymult=0.12)
    g.add("height", "histogram_range", {"input": "shaded"}, range=1.0, position=0.5)
    normal_and_ao(g, "height", intensity=3.0, height_depth=0.25, spreading=0.06)
    g.bind("normal", "intensity", lerp(1.0, 6.0, get("pile_depth")).graph())

    # ---- colour ------------------------------------------------------------------------------
    g.add("yarn", "uniform", outputcolor=(0.42, 0.36, 0.30, 1.0))
    g.bind("yarn", "outputcolor", vector(get("carpet_color", 3), 1.0).graph())
    g.add("tuft_id", "blend", {"source": "tufts_b", "destination": "tufts_a"},
          blendingmode=ADD_SUB, opacitymult=0.5)
    gradient_over(g, "yarn_tufts", "tuft_tones", "tuft_id",
                  [(0.0, (0.36, 0.36, 0.36)), (0.5, (0.50, 0.50, 0.50)), (1.0, (0.64, 0.63, 0.62))], "yarn",
                  blendingmode=SOFT_LIGHT, opacitymult=0.5)
    g.bind("yarn_tufts", "opacitymult", lerp(0.0, 1.0, get("color_variation")).graph())
    gradient_over(g, "yarn_heather", "heather_tones", "fibres", [(0.0, (0.38, 0.38, 0.38)), (1.0, (0.62, 0.62, 0.62))],
                  "yarn_tufts", blendingmode=SOFT_LIGHT, opacitymult=0.4)
    g.bind("yarn_heather", "opacitymult", lerp(0.1, 0.8, get("color_variation")).graph())
    gradient_over(g, "yarn_depth", "depth_tones", "height",
                  [(0.0, (0.30, 0.30, 0.30)), (0.5, (0.78, 0.78, 0.78)), (1.0, (1.0, 1.0, 1.0))], "yarn_heather",
                  blendingmode=MULTIPLY, opacitymult=0.5)
    g.bind("yarn_depth", "opacitymult", lerp(0.2, 0.8, get("pile_depth")).graph())
    ao_darken(g, "basecolor", "yarn_depth", floor=0.25, opacitymult=0.5)

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_inv", "invert_grayscale", {"source": "height"})
    g.add("roughness", "histogram_range", {"input": "rough_inv"}, range=0.1, position=0.9)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "fabric"

SAMPLE_RANGES = {
    "exposed.carpet_color": ((0.04, 0.04, 0.04), (0.80, 0.75, 0.72)),
    "exposed.color_variation": (0.1, 0.8),
    "exposed.tuft_size": (0.1, 0.9),
    "exposed.fuzz": (0.2, 0.9),
    "exposed.pile_depth": (0.2, 0.9),
    "tufts_a.position_random": (0.25, 0.45),
    "tufts_a.mask_random": (0.0, 0.1),
    "tufts_b.mask_random": (0.0, 0.15),
    "tufts_a.scale_random": (0.1, 0.5),
    "tufts_b.position_random": (0.2, 0.5),
    "curls.scale": (5.0, 7.0),
    "shaded.opacitymult": (0.0, 0.25),
    "roughness.position": (0.8, 0.95),
    "tuft_tones.colors": ((0.32, 0.32, 0.32, 1.0, 0.46, 0.46, 0.46, 1.0, 0.58, 0.57, 0.56, 1.0),
                          (0.40, 0.40, 0.40, 1.0, 0.54, 0.54, 0.54, 1.0, 0.68, 0.67, 0.66, 1.0)),
}
