"""Material: hand-hammered metal sheet (copper, brass or steel) with overlapping round shallow dents.

Structure
- Dents: each hammer blow leaves a shallow spherical cup. The distance to the nearest blow
  (Cells 2, a Worley F1 field) squared is exactly such a cup field: low at each blow's centre,
  rising to a sharp ridge where two cups meet. Two fields of blows (a main one and a finer,
  shifted one) overlap with a Min blend, because a later blow only ever removes metal; a little
  cloud warp keeps the cups from looking like a regular cell pattern.
- Height: the cups, levelled by the exposed depth, plus a very faint large-scale waviness of the
  sheet (clouds); normal from it at a high intensity so every cup is a separate mirror facet
  that catches the flash, the ridges between them showing as crisp lines.
- Colour: the exposed metal colour, a touch brighter on the ridges (they are burnished by the
  hammer), with a tarnish layer (exposed amount) that darkens and browns the cup bottoms and
  large cloudy areas, the way copper and brass oxidise between polishings.
- Roughness: low (polished facets) around the exposed value, rougher where tarnished.
  Metallic: 1 on bare metal, lowered under heavy tarnish (oxide is a dielectric film).

Exposed parameters
- ``metal_color`` (float3): the metal's tint: copper, brass, steel or a dark patinated bronze.
- ``dent_depth``: how deep the hammer cups are (relief and facet contrast).
- ``roughness``: mean roughness of the polished facets.
- ``tarnish``: amount of dark oxidation in the cups and in large patches.
- ``hammer_disorder``: how much the blows are scattered off a regular grid and distorted.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD,
    ADD_SUB,
    MIN,
    MULTIPLY,
    SCREEN,
    SUBTRACT,
    color_over,
    gradient_over,
    normal_and_ao,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("hammered_metal")
    g.expose("metal_color", (0.85, 0.52, 0.38), min=0.0, max=1.0)
    g.expose("dent_depth", 0.45, min=0.0, max=1.0)
    g.expose("roughness", 0.22, min=0.05, max=0.7)
    g.expose("tarnish", 0.25, min=0.0, max=1.0)
    g.expose("hammer_disorder", 0.4, min=0.0, max=1.0)

    # ---- hammer blows ---------------------------------------------------------------------------
    g.add("blows_main", "cells_2", seed=71, scale=11, disorder=0.7)
    g.add("blows_fine", "cells_2", seed=72, scale=17, disorder=0.8)
    g.add("sheet_clouds", "clouds_1", seed=73, scale=1.0)
    g.add("warp_noise", "perlin_noise_1", seed=74, scale=6.0)
    g.add("main_warp", "warp", {"input1": "blows_main", "inputgradient": "warp_noise"}, intensity=0.1)
    g.bind("main_warp", "intensity", lerp(0.0, 0.25, get("hammer_disorder")).graph())
    g.add("fine_warp", "warp", {"input1": "blows_fine", "inputgradient": "warp_noise"}, intensity=0.08)
    g.bind("fine_warp", "intensity", lerp(0.0, 0.2, get("hammer_disorder")).graph())
    # a cup is the squared distance to its blow
    g.add("cups_main", "blend", {"source": "main_warp", "destination": "main_warp"},
          blendingmode=MULTIPLY)
    g.add("cups_fine", "blend", {"source": "fine_warp", "destination": "fine_warp"},
          blendingmode=MULTIPLY)
    g.add("cups_fine_level", "histogram_range", {"input": "cups_fine"}, range=0.8, position=0.45)
    g.add("cups", "blend", {"source": "cups_fine_level", "destination": "cups_main"},
          blendingmode=MIN, opacitymult=0.85)
    g.add("cups_norm", "auto_levels", {"input": "cups"})

    # ---- height and normal ------------------------------------------------------------------------
    g.add("cup_depth", "histogram_range", {"input": "cups_norm"}, range=0.6, position=0.5)
    g.bind("cup_depth", "range", lerp(0.05, 0.8, get("dent_depth")).graph())
    g.add("height", "blend", {"source": "sheet_clouds", "destination": "cup_depth"},
          blendingmode=ADD_SUB, opacitymult=0.08)
    normal_and_ao(g, "height", intensity=3.0, height_depth=0.3, spreading=0.1)

    # ---- tarnish mask ---------------------------------------------------------------------------------
    g.add("tarnish_clouds", "clouds_1", seed=75, scale=2.0)
    g.add("cup_bottoms", "invert_grayscale", {"source": "cups_norm"})
    g.add("tarnish_raw", "blend", {"source": "cup_bottoms", "destination": "tarnish_clouds"},
          blendingmode=MULTIPLY, opacitymult=0.6)
    g.add("tarnish_mask", "histogram_scan", {"input_1": "tarnish_raw"}, position=0.3, contrast=0.1)
    g.bind("tarnish_mask", "position", lerp(0.0, 0.85, get("tarnish")).graph())

    # ---- colour ----------------------------------------------------------------------------------------
    g.add("tint", "uniform", outputcolor=(0.85, 0.52, 0.38, 1.0))
    g.bind("tint", "outputcolor", vector(get("metal_color", 3), 1.0).graph())
    gradient_over(g, "tint_ridges", "ridge_tone", "cups_norm",
                  [(0.0, (0.86, 0.86, 0.86)), (0.7, (0.95, 0.95, 0.95)), (1.0, (1.0, 1.0, 1.0))], "tint",
                  blendingmode=MULTIPLY)
    gradient_over(g, "tint_mottled", "sheet_tone", "sheet_clouds",
                  [(0.0, (0.12, 0.12, 0.12)), (1.0, (0.28, 0.28, 0.28))], "tint_ridges", blendingmode=SCREEN,
                  opacitymult=0.4)
    color_over(g, "oxide_on_metal", "oxide_color", (0.16, 0.10, 0.07, 1.0), "tint_mottled", blendingmode=MULTIPLY,
               opacitymult=0.85)
    g.add("basecolor", "blend", {"source": "oxide_on_metal", "destination": "tint_mottled",
                                 "opacity": "tarnish_mask"}, opacitymult=0.85)

    # ---- roughness and metallic ------------------------------------------------------------------------
    g.add("rough_base", "histogram_range", {"input": "cups_norm"}, range=0.1, position=0.22)
    g.bind("rough_base", "position", get("roughness").graph())
    g.add("roughness", "blend", {"source": "tarnish_mask", "destination": "rough_base"},
          blendingmode=ADD, opacitymult=0.2)
    g.add("metal_full", "uniform", colorswitch=False, outputcolor=(1.0, 1.0, 1.0, 1.0))
    g.add("metallic", "blend", {"source": "tarnish_mask", "destination": "metal_full"},
          blendingmode=SUBTRACT, opacitymult=0.5)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "metal"

SAMPLE_RANGES = {
    "exposed.metal_color": ((0.25, 0.20, 0.16), (0.95, 0.80, 0.68)),
    "exposed.dent_depth": (0.25, 0.95),
    "exposed.roughness": (0.1, 0.45),
    "exposed.tarnish": (0.0, 0.7),
    "exposed.hammer_disorder": (0.1, 0.9),
    "blows_main.disorder": (0.4, 1.0),
    "cups.opacitymult": (0.4, 1.0),
    "normal.intensity": (1.5, 6.0),
    "tarnish_clouds.scale": (1.0, 4.0),
    "tint_mottled.opacitymult": (0.1, 0.7),
    "sheet_tone.colors": ([0.10, 0.10, 0.10, 1.0, 0.25, 0.25, 0.25, 1.0],
                          [0.14, 0.14, 0.14, 1.0, 0.31, 0.31, 0.31, 1.0]),
    "ridge_tone.colors": ([0.82, 0.82, 0.82, 1.0, 0.93, 0.93, 0.93, 1.0, 1.0, 1.0, 1.0, 1.0],
                          [0.90, 0.90, 0.90, 1.0, 0.97, 0.97, 0.97, 1.0, 1.0, 1.0, 1.0, 1.0]),
    "oxide_color.outputcolor": ([0.10, 0.06, 0.04, 1.0], [0.22, 0.15, 0.11, 1.0]),
    "ao.height_depth": (0.2, 0.45),
    "ao.spreading": (0.06, 0.2),
}
