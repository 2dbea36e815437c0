"""Slate: a natural cleft slate slab, dark blue-grey, with flaky cleavage steps and a faint sheen.

Structure
- Cleavage steps: a noise stretched along the cleavage direction (Directional Noise), wobbled by
  clouds, mapped through a stepped gradient (no interpolation between keys) so it becomes a few
  flat terraces with irregular heights: the thin layers that split off a cleft slate. Their edges
  are frayed by a min-mode slope blur along a fractal noise (flakes break off unevenly).
- Faces: each terrace keeps a little of the smooth noise (faces are not perfectly flat), plus a
  fine anisotropic grain along the cleavage and a fine fractal roughness.
- Step edges (edge detection of the terraces) read lighter and rougher in the colour: freshly
  broken layers are paler and duller than the weathered face.
- Colour: the exposed slate colour, mottled by soft clouds and a faint cleavage-parallel streak;
  a few rusty/paler flecks (pyrite and quartz) from thresholded noise.
- Roughness: the exposed level on the faces (the sheen of the fine mica), rougher on the step
  edges and flakes. Metallic 0. AO from the height so the step risers shade.

Exposed parameters
- ``slate_color`` (float3): the slate colour (black, blue-grey, green-grey, purple-grey).
- ``steps``: how high the cleavage steps stand (height and normal of the terraces).
- ``flakiness``: how ragged the step edges are and how strong the fine flaky grain is.
- ``edge_lightness``: how much paler the broken step edges are.
- ``roughness``: mean roughness of the faces (lower = more sheen).
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD,
    ADD_SUB,
    COPY,
    MULTIPLY,
    OUR_OCCLUSION,
    color_over,
    constant_map,
    gradient_keys,
    gradient_over,
    pinned_keys,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph

TERRACES = [(0.0, (0.05, 0.05, 0.05)), (0.2, (0.22, 0.22, 0.22)), (0.33, (0.3, 0.3, 0.3)),
            (0.45, (0.46, 0.46, 0.46)), (0.56, (0.55, 0.55, 0.55)), (0.66, (0.7, 0.7, 0.7)),
            (0.8, (0.82, 0.82, 0.82)), (0.9, (0.95, 0.95, 0.95))]
MOTTLE = [(0.0, (0.42, 0.42, 0.43)), (1.0, (0.58, 0.58, 0.57))]
AO_TONE = [(0.0, (0.4, 0.4, 0.4)), (1.0, (1.0, 1.0, 1.0))]
STREAK = [(0.0, (0.46, 0.46, 0.46)), (1.0, (0.54, 0.54, 0.55))]


def build() -> SbsGraph:
    g = SbsGraph("slate")
    g.expose("slate_color", (0.2, 0.21, 0.22), min=0.0, max=1.0)
    g.expose("steps", 0.5, min=0.0, max=1.0)
    g.expose("flakiness", 0.5, min=0.0, max=1.0)
    g.expose("edge_lightness", 0.4, min=0.0, max=1.0)
    g.expose("roughness", 0.5, min=0.2, max=0.9)

    # ---- cleavage terraces --------------------------------------------------------------------
    g.add("layer_broad", "clouds_1", seed=60, scale=2.0)
    g.add("layer_noise", "directionnal_noise", seed=61, scale=1.0)
    g.add("layer_mix", "blend", {"source": "layer_noise", "destination": "layer_broad"}, blendingmode=ADD_SUB,
          opacitymult=0.35)
    g.add("layer_smooth", "blur_hq_grayscale", {"source": "layer_mix"}, intensity=2.5)
    g.add("layer_norm", "auto_levels", {"input": "layer_smooth"})
    g.add("wobble", "clouds_2", seed=62, scale=3.0)
    g.add("layer_warp", "warp", {"input1": "layer_norm", "inputgradient": "wobble"}, intensity=0.04)
    g.add("terraces", "gradient", {"input1": "layer_warp"}, interpmode=3, colorswitch=False,
          **gradient_keys(TERRACES))
    g.add("fray_noise", "fractal_sum_4", seed=63, scale=2.0)
    g.add("frayed", "slope_blur_grayscale", {"source": "terraces", "effect": "fray_noise"}, samples=4,
          mode=6, intensity=2.0)
    g.bind("frayed", "intensity", lerp(0.0, 5.0, get("flakiness")).graph())
    g.add("faces", "blend", {"source": "layer_warp", "destination": "frayed"}, blendingmode=ADD_SUB,
          opacitymult=0.12)

    # ---- fine grain ---------------------------------------------------------------------------
    g.add("grain_dir", "anisotropic_noise", seed=64, x_amount=4, y_amount=128, smoothness=0.6)
    g.add("grain_fine", "fractal_sum_1", seed=65, scale=16.0, roughness=0.6)
    g.add("grain", "blend", {"source": "grain_dir", "destination": "grain_fine"}, blendingmode=ADD_SUB,
          opacitymult=0.3)

    # ---- height -------------------------------------------------------------------------------
    g.add("step_level", "histogram_range", {"input": "faces"}, range=0.5, position=0.5)
    g.bind("step_level", "range", lerp(0.05, 1.0, get("steps")).graph())
    g.add("grained", "blend", {"source": "grain", "destination": "step_level"}, blendingmode=ADD_SUB,
          opacitymult=0.08)
    g.bind("grained", "opacitymult", lerp(0.004, 0.035, get("flakiness")).graph())
    g.add("height", "histogram_range", {"input": "grained"}, range=1.0, position=0.5)
    g.add("normal_main", "normal", {"input1": "height"}, intensity=10.0, inversedy=True, input2alpha=False)
    g.add("normal_grain", "normal", {"input1": "grain"}, intensity=0.3, inversedy=True, input2alpha=False)
    g.add("normal", "normal_combine", {"input": "normal_main", "input_1": "normal_grain"})
    g.add("ao", "ambient_occlusion_2", {"source": "height"}, height_depth=0.15, spreading=0.08,
          model=OUR_OCCLUSION)

    # ---- step edges ---------------------------------------------------------------------------
    g.add("edges", "edge_detect", {"input": "frayed"}, edge_width=1.5, edge_roundness=1.0, tolerance=0.02,
          invert=True)
    g.add("edges_soft", "blur", {"input1": "edges"}, intensity=0.6)

    # ---- colour -------------------------------------------------------------------------------
    g.add("slate", "uniform", outputcolor=(0.2, 0.21, 0.22, 1.0))
    g.bind("slate", "outputcolor", vector(get("slate_color", 3), 1.0).graph())
    g.add("mottle_noise", "clouds_2", seed=66, scale=2.0)
    gradient_over(g, "col_mottle", "mottle", "mottle_noise", MOTTLE, "slate", blendingmode=ADD_SUB, opacitymult=0.2)
    gradient_over(g, "col_streak", "streak", "grain_dir", STREAK, "col_mottle", blendingmode=ADD_SUB, opacitymult=0.2)
    color_over(g, "col_edges", "edge_color", (0.3, 0.3, 0.31, 1.0), "col_streak", mask="edges_soft", blendingmode=ADD,
               opacitymult=0.3)
    g.bind("col_edges", "opacitymult", lerp(0.0, 0.5, get("edge_lightness")).graph())
    g.add("fleck_noise", "white_noise", seed=67)
    g.add("flecks", "histogram_scan", {"input_1": "fleck_noise"}, position=0.01, contrast=0.85)
    g.add("flecks_soft", "blur", {"input1": "flecks"}, intensity=0.4)
    color_over(g, "col_flecks", "fleck_color", (0.42, 0.36, 0.28, 1.0), "col_edges", mask="flecks_soft",
               blendingmode=COPY, opacitymult=0.5)
    gradient_over(g, "basecolor", "ao_tone", "ao", AO_TONE, "col_flecks", blendingmode=MULTIPLY, opacitymult=0.4)

    # ---- roughness ----------------------------------------------------------------------------
    g.add("r_base", "histogram_range", {"input": "grain_fine"}, range=0.12, position=0.5)
    g.bind("r_base", "position", get("roughness").graph())
    g.add("roughness", "blend", {"source": "edges_soft", "destination": "r_base"}, blendingmode=ADD,
          opacitymult=0.2)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "stone"


SAMPLE_RANGES = {
    "exposed.slate_color": ((0.1, 0.1, 0.1), (0.27, 0.29, 0.31)),
    "exposed.steps": (0.2, 0.9),
    "exposed.flakiness": (0.1, 0.9),
    "exposed.edge_lightness": (0.1, 0.8),
    "exposed.roughness": (0.3, 0.7),
    "layer_warp.intensity": (0.01, 0.08),
    "layer_noise.scale": (1.0, 2.0),
    "layer_mix.opacitymult": (0.2, 0.5),
    "layer_smooth.intensity": (1.0, 5.0),
    "faces.opacitymult": (0.05, 0.25),
    "normal_main.intensity": (5.0, 16.0),
    "flecks.position": (0.0, 0.03),
    "flecks_soft.intensity": (0.2, 0.6),
    "edges_soft.intensity": (0.3, 1.0),
    "normal_grain.intensity": (0.1, 0.6),
    "fleck_color.outputcolor": ((0.35, 0.3, 0.22, 1.0), (0.55, 0.5, 0.45, 1.0)),
    "edge_color.outputcolor": ((0.25, 0.25, 0.26, 1.0), (0.35, 0.35, 0.36, 1.0)),
    **{f"{node}.{p}": r for node, stops in (("terraces", TERRACES), ("mottle", MOTTLE), ("streak", STREAK),
                                             ("ao_tone", AO_TONE))
       for p, r in pinned_keys(stops).items()},
}
