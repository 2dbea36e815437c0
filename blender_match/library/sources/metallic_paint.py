"""Material: car-style metallic paint, fine sparkling flakes under a glossy clear coat with slight orange peel.

Structure
- Flakes: a fine Voronoi mosaic of random levels (Cells 4 at a very high cell count) mixed with
  per-texel white noise: every flake is a tiny plate with its own brightness. A histogram scan
  of the mix keeps the brightest as sparkles (exposed flake amount); a soft version of the mix
  gives the overall shimmer.
- Orange peel: a dense Perlin noise (the clear coat's ripple) on a faint, broad cloud undulation;
  it is most of the height, and so the soft wavy distortion of the flash reflection.
- Flake relief: the flake mosaic as a tiny height in its own normal, combined with the orange-peel
  normal, so neighbouring flakes tilt differently and glint one by one under a flash.
- Colour: the exposed paint colour, each flake lighter or darker around it (the pigment seen
  through a metallic flake is brighter and less saturated), with a very faint cloud mottle.
- Metallic: mid-high (the binder is dielectric, the aluminium flakes metal), highest on the bright
  flakes. Roughness: low (the clear coat), set by the exposed gloss, slightly higher off-flake.

Exposed parameters
- ``paint_color`` (float3): the paint's hue and lightness (any colour).
- ``flake_amount``: how many flakes sparkle, and how strongly they lighten the colour.
- ``metallic``: how metallic the paint reads (pearl/solid-like at 0, strongly metallic at 1).
- ``roughness``: roughness of the clear coat (glossy by default).
- ``orange_peel``: strength of the clear coat's orange-peel ripple.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD,
    ADD_SUB,
    MULTIPLY,
    OVERLAY,
    SCREEN,
    SOFT_LIGHT,
    color_over,
    gradient_over,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("metallic_paint")
    g.expose("paint_color", (0.55, 0.06, 0.08), min=0.0, max=1.0)
    g.expose("flake_amount", 0.5, min=0.0, max=1.0)
    g.expose("metallic", 0.6, min=0.0, max=1.0)
    g.expose("roughness", 0.12, min=0.02, max=0.6)
    g.expose("orange_peel", 0.3, min=0.0, max=1.0)

    # ---- flakes ------------------------------------------------------------------------------
    g.add("flake_cells", "cells_4", seed=61, scale=160, disorder=0.8)
    g.add("flake_noise", "white_noise", seed=62)
    g.add("flake_mix", "blend", {"source": "flake_noise", "destination": "flake_cells"},
          blendingmode=OVERLAY, opacitymult=0.6)
    g.add("sparkles", "histogram_scan", {"input_1": "flake_mix"}, contrast=0.6)
    g.bind("sparkles", "position", lerp(0.01, 0.25, get("flake_amount")).graph())
    g.add("shimmer", "histogram_range", {"input": "flake_mix"}, range=0.5, position=0.5)
    g.bind("shimmer", "range", lerp(0.1, 0.7, get("flake_amount")).graph())

    # ---- orange peel -------------------------------------------------------------------------
    g.add("peel_fine", "perlin_noise", seed=63, scale=56.0)
    g.add("peel_coarse", "perlin_noise", seed=64, scale=22.0)
    g.add("peel_mix", "blend", {"source": "peel_coarse", "destination": "peel_fine"},
          blendingmode=OVERLAY, opacitymult=0.5)
    g.add("undulation", "clouds_2", seed=65, scale=2.0)
    g.add("peel_undulated", "blend", {"source": "undulation", "destination": "peel_mix"},
          blendingmode=ADD_SUB, opacitymult=0.12)
    g.add("peel_height", "histogram_range", {"input": "peel_undulated"}, range=0.4, position=0.5)
    g.bind("peel_height", "range", lerp(0.02, 0.5, get("orange_peel")).graph())
    g.add("flake_height", "blend", {"source": "flake_cells", "destination": "peel_height"},
          blendingmode=ADD_SUB, opacitymult=0.02)
    g.add("height", "histogram_range", {"input": "flake_height"}, range=1.0, position=0.5)

    g.add("normal_peel", "normal", {"input1": "peel_height"}, intensity=0.8, inversedy=True)
    g.add("normal_flakes", "normal", {"input1": "flake_mix"}, intensity=0.25, inversedy=True)
    g.add("normal", "normal_combine", {"input": "normal_peel", "input_1": "normal_flakes"})

    # ---- colour ------------------------------------------------------------------------------
    g.add("paint", "uniform", outputcolor=(0.55, 0.06, 0.08, 1.0))
    g.bind("paint", "outputcolor", vector(get("paint_color", 3), 1.0).graph())
    gradient_over(g, "paint_mottled", "mottle", "undulation", [(0.0, (0.46, 0.46, 0.46)), (1.0, (0.54, 0.54, 0.54))],
                  "paint", blendingmode=SOFT_LIGHT, opacitymult=0.6)
    gradient_over(g, "paint_shimmer", "shimmer_tone", "shimmer",
                  [(0.0, (0.8, 0.8, 0.8)), (0.5, (0.95, 0.95, 0.95)), (1.0, (1.0, 1.0, 1.0))], "paint_mottled",
                  blendingmode=MULTIPLY, opacitymult=0.8)
    color_over(g, "basecolor", "sparkle_tone", (0.55, 0.55, 0.56, 1.0), "paint_shimmer", mask="sparkles",
               blendingmode=SCREEN, opacitymult=0.4)

    # ---- metallic and roughness ---------------------------------------------------------------
    g.add("metal_base", "histogram_range", {"input": "shimmer"}, range=0.2, position=0.6)
    g.bind("metal_base", "position", lerp(0.05, 0.85, get("metallic")).graph())
    g.add("metallic", "blend", {"source": "sparkles", "destination": "metal_base"},
          blendingmode=ADD, opacitymult=0.3)
    g.add("rough_base", "histogram_range", {"input": "undulation"}, range=0.05, position=0.18)
    g.bind("rough_base", "position", get("roughness").graph())
    g.add("roughness", "blend", {"source": "shimmer", "destination": "rough_base"},
          blendingmode=ADD_SUB, opacitymult=0.08)

    set_material_outputs(g)
    return g


FAMILY = "coating"

SAMPLE_RANGES = {
    "exposed.paint_color": ((0.02, 0.02, 0.02), (0.85, 0.85, 0.85)),
    "exposed.flake_amount": (0.2, 0.9),
    "exposed.metallic": (0.3, 0.9),
    "exposed.roughness": (0.06, 0.35),
    "exposed.orange_peel": (0.1, 0.8),
    "flake_cells.disorder": (0.4, 1.0),
    "flake_mix.opacitymult": (0.3, 0.9),
    "sparkles.contrast": (0.4, 0.8),
    "peel_mix.opacitymult": (0.2, 0.8),
    "normal_peel.intensity": (0.4, 1.6),
    "normal_flakes.intensity": (0.1, 0.8),
    "basecolor.opacitymult": (0.3, 0.9),
}
