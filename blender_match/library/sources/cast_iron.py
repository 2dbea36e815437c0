"""Material: rough sand-cast grey iron: dark granular surface with small pits and a little rust.

Structure
- Sand grain: a casting takes the print of its sand mould, a dense granular relief of about a
  millimetre. BnW Spots 3 at a fine scale (speckle over mottling) plus a slightly blurred white
  noise give the grain; a Gaussian noise adds the coarser lumps of packed sand.
- Pits: gas pores and sand inclusions leave small round pits. The distance to scattered points
  (Cells 2) below a threshold gives round dots at random places; a BnW Spots 1 mask keeps only
  some of them, so they cluster irregularly instead of filling a lattice; a Gaussian noise
  varies their depth.
- Height: grain + lumps + a soft large undulation of the casting, minus the pits; normal from it
  (strong enough for a crisp grain under the flash); ambient occlusion from it.
- Colour: the exposed iron colour, darker in the hollows, lighter on the grain peaks where
  handling has rubbed the skin (exposed wear); rust (orange-brown) collects in the pits and in
  patches of the hollows (exposed amount).
- Roughness: mostly rough around the exposed value, the rubbed peaks smoother, rust roughest.
  Metallic: 1 on the iron (a little less on the dull casting skin), 0 under rust.

Exposed parameters
- ``iron_color`` (float3): the grey of the casting skin (blue-grey to warm dark grey).
- ``grain_depth``: strength of the sand-grain relief.
- ``pitting``: how many pits, and how deep.
- ``rust``: amount of rust in pits and hollows.
- ``roughness``: mean roughness of the iron.
- ``wear``: rubbed, lighter and smoother grain peaks.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD,
    ADD_SUB,
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
    g = SbsGraph("cast_iron")
    g.expose("iron_color", (0.47, 0.47, 0.48), min=0.0, max=1.0)
    g.expose("grain_depth", 0.55, min=0.0, max=1.0)
    g.expose("pitting", 0.4, min=0.0, max=1.0)
    g.expose("rust", 0.3, min=0.0, max=1.0)
    g.expose("roughness", 0.55, min=0.3, max=1.0)
    g.expose("wear", 0.3, min=0.0, max=1.0)

    # ---- sand grain --------------------------------------------------------------------------------
    g.add("grain_spots", "bnw_spots_3", seed=101, scale=16.0)
    g.add("speck", "white_noise", seed=102)
    g.add("speck_soft", "blur_hq_grayscale", {"source": "speck"}, intensity=0.6)
    g.add("speck_level", "auto_levels", {"input": "speck_soft"})
    g.add("lumps", "gaussian_noise", seed=103, scale=2.0)
    g.add("grain_mix", "blend", {"source": "speck_level", "destination": "grain_spots"},
          blendingmode=ADD_SUB, opacitymult=0.35)
    g.add("grain_lumps", "blend", {"source": "lumps", "destination": "grain_mix"},
          blendingmode=ADD_SUB, opacitymult=0.5)
    g.add("grain", "auto_levels", {"input": "grain_lumps"})

    # ---- pits -------------------------------------------------------------------------------------------
    g.add("pit_points", "cells_2", seed=104, scale=24, disorder=0.9)
    g.add("pit_near", "invert_grayscale", {"source": "pit_points"})
    g.add("pit_dots", "histogram_scan", {"input_1": "pit_near"}, position=0.2, contrast=0.75)
    g.add("pit_clusters", "bnw_spots_1", seed=105, scale=6.0)
    g.add("pit_cluster_mask", "histogram_scan", {"input_1": "pit_clusters"}, position=0.4, contrast=0.6)
    g.bind("pit_cluster_mask", "position", lerp(0.05, 0.85, get("pitting")).graph())
    g.add("pits_kept", "blend", {"source": "pit_cluster_mask", "destination": "pit_dots"},
          blendingmode=MULTIPLY)
    g.add("pit_depth_noise", "gaussian_noise", seed=106, scale=4.0)
    g.add("pit_depth_var", "histogram_range", {"input": "pit_depth_noise"}, range=0.6, position=0.7)
    g.add("pits", "blend", {"source": "pit_depth_var", "destination": "pits_kept"},
          blendingmode=MULTIPLY)
    g.add("pits_soft", "blur_hq_grayscale", {"source": "pits"}, intensity=0.5)

    # ---- height and normal ---------------------------------------------------------------------------------
    g.add("grain_level", "histogram_range", {"input": "grain"}, range=0.5, position=0.55)
    g.bind("grain_level", "range", lerp(0.05, 0.8, get("grain_depth")).graph())
    g.add("casting_wave", "clouds_1", seed=107, scale=1.0)
    g.add("waved", "blend", {"source": "casting_wave", "destination": "grain_level"},
          blendingmode=ADD_SUB, opacitymult=0.15)
    g.add("height", "blend", {"source": "pits_soft", "destination": "waved"},
          blendingmode=SUBTRACT, opacitymult=0.45)
    g.bind("height", "opacitymult", lerp(0.1, 0.7, get("pitting")).graph())
    normal_and_ao(g, "height", intensity=2.0, height_depth=0.3, spreading=0.08)

    # ---- masks: rubbed peaks, rust ------------------------------------------------------------------------------
    g.add("peaks", "histogram_scan", {"input_1": "height"}, position=0.25, contrast=0.4)
    g.bind("peaks", "position", lerp(0.0, 0.7, get("wear")).graph())
    g.add("hollows", "invert_grayscale", {"source": "height"})
    g.add("rust_clouds", "clouds_2", seed=108, scale=2.0)
    g.add("rust_hollows", "blend", {"source": "rust_clouds", "destination": "hollows"},
          blendingmode=MULTIPLY)
    g.add("rust_with_pits", "blend", {"source": "pits_soft", "destination": "rust_hollows"},
          blendingmode=SCREEN)
    g.add("rust_mask", "histogram_scan", {"input_1": "rust_with_pits"}, position=0.2, contrast=0.5)
    g.bind("rust_mask", "position", lerp(0.0, 0.6, get("rust")).graph())

    # ---- colour -------------------------------------------------------------------------------------------------
    g.add("iron", "uniform", outputcolor=(0.47, 0.47, 0.48, 1.0))
    g.bind("iron", "outputcolor", vector(get("iron_color", 3), 1.0).graph())
    # iron is nearly neutral: keep the colour's lightness, only a hint of its hue
    g.add("iron_luma", "grayscaleconversion", {"input1": "iron"})
    gradient_over(g, "iron_neutral", "iron_gray", "iron_luma", [(0.0, (0.0, 0.0, 0.0)), (1.0, (1.0, 1.0, 1.0))], "iron",
                  opacitymult=0.75)
    gradient_over(g, "iron_shaded", "hollow_tone", "height",
                  [(0.0, (0.45, 0.45, 0.45)), (0.5, (0.85, 0.85, 0.85)), (1.0, (1.0, 1.0, 1.0))], "iron_neutral",
                  blendingmode=MULTIPLY)
    color_over(g, "iron_rubbed", "rub_tone", (0.20, 0.20, 0.20, 1.0), "iron_shaded", mask="peaks", blendingmode=ADD,
               opacitymult=0.7)
    gradient_over(g, "basecolor", "rust_color", "rust_clouds", [(0.0, (0.22, 0.10, 0.05)), (1.0, (0.42, 0.20, 0.08))],
                  "iron_rubbed", mask="rust_mask", opacitymult=0.85)

    # ---- roughness and metallic -----------------------------------------------------------------------------------
    g.add("rough_base", "histogram_range", {"input": "hollows"}, range=0.15, position=0.75)
    g.bind("rough_base", "position", get("roughness").graph())
    g.add("rough_rubbed", "blend", {"source": "peaks", "destination": "rough_base"},
          blendingmode=SUBTRACT, opacitymult=0.25)
    g.add("rough_rust", "uniform", colorswitch=False, outputcolor=(0.95, 0.95, 0.95, 1.0))
    g.add("roughness", "blend", {"source": "rough_rust", "destination": "rough_rubbed",
                                 "opacity": "rust_mask"})
    g.add("metal_skin", "uniform", colorswitch=False, outputcolor=(0.85, 0.85, 0.85, 1.0))
    g.add("metal_rubbed", "blend", {"source": "peaks", "destination": "metal_skin"},
          blendingmode=ADD, opacitymult=0.3)
    g.add("metallic", "blend", {"source": "rust_mask", "destination": "metal_rubbed"},
          blendingmode=SUBTRACT)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "metal"

SAMPLE_RANGES = {
    "exposed.iron_color": ((0.28, 0.28, 0.29), (0.58, 0.58, 0.60)),
    "exposed.grain_depth": (0.25, 0.9),
    "exposed.pitting": (0.0, 0.9),
    "exposed.rust": (0.0, 0.7),
    "exposed.roughness": (0.45, 0.9),
    "exposed.wear": (0.0, 0.8),
    "grain_spots.scale": (10.0, 24.0),
    "grain_mix.opacitymult": (0.1, 0.6),
    "grain_lumps.opacitymult": (0.2, 0.8),
    "pit_dots.position": (0.08, 0.25),
    "normal.intensity": (1.5, 5.0),
    "rust_clouds.scale": (1.0, 4.0),
    "hollow_tone.colors": ([0.43, 0.43, 0.43, 1.0, 0.83, 0.83, 0.83, 1.0, 1.0, 1.0, 1.0, 1.0],
                           [0.47, 0.47, 0.47, 1.0, 0.87, 0.87, 0.87, 1.0, 1.0, 1.0, 1.0, 1.0]),
    "iron_neutral.opacitymult": (0.65, 0.9),
    "iron_luma.channelsweights": ([0.33, 0.33, 0.33, 0.0], [0.33, 0.33, 0.33, 0.0]),
    "iron_gray.colors": ([0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0], [0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0]),
    "rust_color.colors": ([0.19, 0.09, 0.04, 1.0, 0.38, 0.18, 0.07, 1.0],
                          [0.25, 0.11, 0.06, 1.0, 0.46, 0.22, 0.09, 1.0]),
    "rub_tone.outputcolor": ([0.18, 0.18, 0.18, 1.0], [0.22, 0.22, 0.22, 1.0]),
}
