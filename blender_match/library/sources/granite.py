"""Granite: a polished or honed speckled granite slab of interlocking feldspar, quartz and dark mica crystals.

Structure
- Crystals: two Voronoi mosaics of random gray levels (Cells 4), a fine one (quartz and dark
  minerals, about 2-4 mm on a 30 cm sample) and a coarser one (feldspar, 4-8 mm), each warped by
  a fine noise so the crystal outlines are angular and interlocking instead of polygon-clean.
- Minerals: histogram scans of the two mosaics pick which crystals are feldspar (coarse mosaic)
  and which are dark biotite/hornblende (fine mosaic); the remaining crystals are grey,
  translucent-looking quartz. Granites are told apart by their feldspar colour (grey, black, pink,
  beige), so that colour is exposed; the per-crystal gray level varies every crystal's shade.
- Colour: the feldspar colour a little desaturated (an HSL node: natural feldspars are muted),
  quartz grey (varied per crystal) under the feldspar colour (masked, shaded per crystal)
  under the dark minerals; a fine white-noise sparkle of tiny light grains; a faint cloudy tone
  variation across the slab.
- Height: almost flat (a polished slab): dark micas and crystal boundaries are a hair lower (they
  pluck out in polishing), plus a few tiny pits. Normal from it, weak. AO barely matters on a
  flat slab, so none.
- Roughness: the exposed polish level; micas and pits rougher (they do not take a polish).
  Metallic 0.

Exposed parameters
- ``feldspar_color`` (float3): colour of the feldspar crystals, the granite's main hue.
- ``dark_minerals``: share of dark crystals (salt-and-pepper grey granite vs. black granite).
- ``quartz_tone``: lightness of the quartz crystals (light grey to smoky dark).
- ``crystal_contrast``: how much each crystal's shade differs from its neighbours.
- ``roughness``: the finish: polished (low) or honed (higher).
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD,
    ADD_SUB,
    COPY,
    MULTIPLY,
    SUBTRACT,
    color_over,
    constant_map,
    gradient_keys,
    gradient_over,
    pinned_keys,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph

QUARTZ = [(0.0, (0.5, 0.5, 0.51)), (1.0, (0.8, 0.8, 0.8))]
FELDSPAR_SHADE = [(0.0, (0.55, 0.55, 0.55)), (0.55, (0.5, 0.5, 0.5)), (1.0, (0.75, 0.75, 0.75))]
DARK_TONE = [(0.0, (0.03, 0.03, 0.03)), (1.0, (0.13, 0.12, 0.11))]
SLAB_TONE = [(0.0, (0.44, 0.44, 0.44)), (1.0, (0.56, 0.56, 0.56))]
CRYSTAL_VAR = [(0.0, (0.42, 0.42, 0.42)), (1.0, (0.58, 0.58, 0.58))]


def build() -> SbsGraph:
    g = SbsGraph("granite")
    g.expose("feldspar_color", (0.76, 0.44, 0.38), min=0.0, max=1.0)
    g.expose("dark_minerals", 0.35, min=0.0, max=1.0)
    g.expose("quartz_tone", 0.75, min=0.0, max=1.0)
    g.expose("crystal_contrast", 0.5, min=0.0, max=1.0)
    g.expose("roughness", 0.15, min=0.03, max=0.6)

    # ---- crystal mosaics ----------------------------------------------------------------------
    g.add("edge_noise", "perlin_noise", seed=51, scale=24.0)
    g.add("fine_cells", "cells_4", seed=52, scale=80, disorder=0.9)
    g.add("fine_warp", "warp", {"input1": "fine_cells", "inputgradient": "edge_noise"}, intensity=0.06)
    g.add("coarse_cells", "cells_4", seed=53, scale=44, disorder=0.9)
    g.add("coarse_noise", "perlin_noise", seed=54, scale=16.0)
    g.add("coarse_warp", "warp", {"input1": "coarse_cells", "inputgradient": "coarse_noise"}, intensity=0.12)

    # ---- mineral masks ------------------------------------------------------------------------
    g.add("feldspar_mask", "histogram_scan", {"input_1": "coarse_warp"}, position=0.5, contrast=0.96)
    g.add("dark_mask", "histogram_scan", {"input_1": "fine_warp"}, position=0.3, contrast=0.96)
    g.bind("dark_mask", "position", lerp(0.02, 0.6, get("dark_minerals")).graph())
    g.add("dark_soft", "blur", {"input1": "dark_mask"}, intensity=0.3)

    # ---- colour -------------------------------------------------------------------------------
    g.add("quartz", "gradient", {"input1": "fine_warp"}, **gradient_keys(QUARTZ))
    g.add("quartz_level", "uniform", outputcolor=(0.5, 0.5, 0.5, 1.0))
    g.bind("quartz_level", "outputcolor", vector(lerp(0.15, 1.0, get("quartz_tone")),
                                                 lerp(0.15, 1.0, get("quartz_tone")),
                                                 lerp(0.15, 1.0, get("quartz_tone")), 1.0).graph())
    g.add("quartz_toned", "blend", {"source": "quartz_level", "destination": "quartz"},
          blendingmode=MULTIPLY, opacitymult=1.0)
    g.add("feldspar", "uniform", outputcolor=(0.76, 0.44, 0.38, 1.0))
    g.bind("feldspar", "outputcolor", vector(get("feldspar_color", 3), 1.0).graph())
    g.add("feldspar_shade", "gradient", {"input1": "coarse_warp"}, **gradient_keys(FELDSPAR_SHADE))
    g.add("feldspar_muted", "hsl", {"input1": "feldspar"}, hue=0.5, saturation=0.4, luminosity=0.5)
    g.add("feldspar_shaded", "blend", {"source": "feldspar_shade", "destination": "feldspar_muted"},
          blendingmode=ADD_SUB, opacitymult=0.5)
    g.bind("feldspar_shaded", "opacitymult", lerp(0.0, 0.9, get("crystal_contrast")).graph())
    g.add("col_feldspar", "blend", {"source": "feldspar_shaded", "destination": "quartz_toned",
                                    "opacity": "feldspar_mask"}, blendingmode=COPY, opacitymult=1.0)
    gradient_over(g, "col_dark", "dark_tone", "fine_cells", DARK_TONE, "col_feldspar", mask="dark_soft",
                  blendingmode=COPY, opacitymult=1.0)
    g.add("sparkle_noise", "white_noise", seed=55)
    g.add("sparkle", "histogram_scan", {"input_1": "sparkle_noise"}, position=0.03, contrast=0.9)
    color_over(g, "col_sparkle", "sparkle_color", (0.85, 0.84, 0.82, 1.0), "col_dark", mask="sparkle",
               blendingmode=COPY, opacitymult=0.5)
    g.add("slab_clouds", "clouds_2", seed=56, scale=2.0)
    g.add("slab_tone", "gradient", {"input1": "slab_clouds"}, **gradient_keys(SLAB_TONE))
    gradient_over(g, "col_var", "crystal_var", "fine_warp", CRYSTAL_VAR, "col_sparkle", blendingmode=ADD_SUB,
                  opacitymult=0.5)
    g.bind("col_var", "opacitymult", lerp(0.0, 0.8, get("crystal_contrast")).graph())
    g.add("basecolor", "blend", {"source": "slab_tone", "destination": "col_var"},
          blendingmode=ADD_SUB, opacitymult=0.4)

    # ---- height -------------------------------------------------------------------------------
    g.add("boundaries", "edge_detect", {"input": "coarse_warp"}, invert=True)
    g.add("pit_noise", "white_noise", seed=57)
    g.add("pits", "histogram_scan", {"input_1": "pit_noise"}, position=0.015, contrast=0.8,
          invert_position=True)
    g.add("pits_soft", "blur", {"input1": "pits"}, intensity=0.5)
    g.add("h_flat", "histogram_range", {"input": "slab_clouds"}, range=0.05, position=0.7)
    g.add("h_dark", "blend", {"source": "dark_soft", "destination": "h_flat"}, blendingmode=SUBTRACT,
          opacitymult=0.08)
    g.add("h_bound", "blend", {"source": "boundaries", "destination": "h_dark"}, blendingmode=SUBTRACT,
          opacitymult=0.06)
    g.add("height", "blend", {"source": "pits_soft", "destination": "h_bound"}, blendingmode=SUBTRACT,
          opacitymult=0.3)
    g.add("normal", "normal", {"input1": "height"}, intensity=1.5, inversedy=True, input2alpha=False)

    # ---- roughness ----------------------------------------------------------------------------
    g.add("r_base", "histogram_range", {"input": "slab_clouds"}, range=0.04, position=0.15)
    g.bind("r_base", "position", get("roughness").graph())
    g.add("r_dark", "blend", {"source": "dark_soft", "destination": "r_base"}, blendingmode=ADD,
          opacitymult=0.12)
    g.add("roughness", "blend", {"source": "pits_soft", "destination": "r_dark"}, blendingmode=ADD,
          opacitymult=0.4)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g)
    return g


FAMILY = "stone"

SAMPLE_RANGES = {
    "exposed.feldspar_color": ((0.3, 0.22, 0.18), (0.85, 0.58, 0.56)),
    "feldspar_muted.hue": (0.5, 0.5),
    "feldspar_muted.saturation": (0.36, 0.46),
    "feldspar_muted.luminosity": (0.47, 0.53),
    "exposed.dark_minerals": (0.1, 0.85),
    "exposed.quartz_tone": (0.15, 0.9),
    "exposed.crystal_contrast": (0.2, 0.9),
    "exposed.roughness": (0.05, 0.45),
    "feldspar_mask.position": (0.3, 0.7),
    "fine_warp.intensity": (0.02, 0.1),
    "coarse_warp.intensity": (0.05, 0.2),
    "edge_noise.scale": (16.0, 32.0),
    "coarse_noise.scale": (10.0, 24.0),
    "fine_cells.disorder": (0.6, 1.0),
    "sparkle.position": (0.005, 0.06),
    "pits.position": (0.005, 0.03),
    "dark_soft.intensity": (0.0, 0.6),
    "pits_soft.intensity": (0.2, 0.8),
    "normal.intensity": (0.8, 3.0),
    "basecolor.opacitymult": (0.1, 0.6),
    "sparkle_color.outputcolor": ((0.75, 0.75, 0.74, 1.0), (0.9, 0.9, 0.89, 1.0)),
    **{f"{node}.{p}": r for node, stops in (("quartz", QUARTZ), ("feldspar_shade", FELDSPAR_SHADE),
                                             ("dark_tone", DARK_TONE), ("slab_tone", SLAB_TONE),
                                             ("crystal_var", CRYSTAL_VAR))
       for p, r in pinned_keys(stops).items()},
}
