"""Material: tree bark (oak/pine-like): deep vertical furrows between rough, flaky ridges and plates.

Structure
- Plates: cushion-like Voronoi cells (Cells 1) squeezed four times across (an integer
  Transformation 2D, so they still tile) become tall plates separated by dark seams, warped by the
  ridge noise so the seams wander along the ridges like real fissures.
- Ridges: a ridged directional noise (Directional Noise 4, turned a quarter to run vertically) gives the long
  corky ridges and the fibrous strands along the trunk; it is multiplied into the plates so the
  deepest furrows are where both are low.
- Furrows: a histogram scan of the combined relief picks the deep fissures (the exposed depth
  moves it and scales how far they sink); a directional blur drags it along the trunk, so the
  fissures and ridge flanks stay long and vertical.
- Flakes: fine cracks across the plates (Cells 3 edges, squeezed) and a crumbly spot noise roughen
  the ridge tops (exposed).
- Colour: the exposed bark colour on the ridge tops, weathered lighter and greyer on the highest
  faces, dark brown in the furrows (a gradient over the height), with clouds and a little greenish
  lichen in the furrow edges; ambient occlusion darkens the fissures.
- Normal (OpenGL) from the height, strong; roughness nearly fully rough. Metallic 0.

Exposed parameters
- ``bark_color`` (float3): the colour of the ridges (grey-brown).
- ``furrow_depth``: how deep and wide the vertical fissures are.
- ``flakiness``: cracks and crumbly detail on the ridges.
- ``lichen``: greenish-grey growth in the furrow edges.
- ``roughness``: mean roughness.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD_SUB,
    COPY,
    MULTIPLY,
    SOFT_LIGHT,
    SUBTRACT,
    ao_darken,
    color_over,
    constant_map,
    gradient_over,
    keys_near,
    normal_and_ao,
    rgba_near,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph

# height tones: furrows dark, flanks mid, ridge tops weathered lighter (multiplied over the colour)
DEPTH_TONES = [(0.0, (0.18, 0.15, 0.13)), (0.25, (0.52, 0.49, 0.46)), (0.55, (0.88, 0.87, 0.85)),
               (1.0, (1.0, 1.0, 1.0))]
CLOUD_TONES = [(0.0, (0.42, 0.42, 0.42)), (1.0, (0.58, 0.57, 0.55))]
WEATHER_COLOR = (0.62, 0.60, 0.57)
LICHEN_COLOR = (0.45, 0.50, 0.38)


def build() -> SbsGraph:
    g = SbsGraph("bark")
    g.expose("bark_color", (0.44, 0.37, 0.29), min=0.0, max=1.0)
    g.expose("furrow_depth", 0.6, min=0.0, max=1.0)
    g.expose("flakiness", 0.5, min=0.0, max=1.0)
    g.expose("lichen", 0.2, min=0.0, max=1.0)
    g.expose("roughness", 0.88, min=0.5, max=1.0)
    squeeze = (4.0, 0.0, 0.0, 1.0)  # three times narrower across: tall plates

    # ---- plates and ridges -------------------------------------------------------------------
    g.add("cells", "cells_1", seed=101, scale=3, disorder=0.8)
    g.add("plates_tall", "transformation", {"input1": "cells"}, matrix22=squeeze)
    g.add("seam_noise", "perlin_noise_1", seed=102, scale=4.0)
    g.add("ridges_src", "directional_noise_4", seed=103, scale=3.0)
    g.add("ridges", "transformation", {"input1": "ridges_src"}, matrix22=(0.0, 1.0, -1.0, 0.0))
    g.add("plates", "warp", {"input1": "plates_tall", "inputgradient": "seam_noise"}, intensity=0.5)
    g.add("relief", "blend", {"source": "ridges", "destination": "plates"},
          blendingmode=MULTIPLY, opacitymult=0.85)
    g.add("relief_level", "histogram_range", {"input": "relief"}, range=1.0, position=0.5)

    # ---- furrows -----------------------------------------------------------------------------
    g.add("furrows", "histogram_scan", {"input_1": "relief_level"}, position=0.7, contrast=0.2)
    g.bind("furrows", "position", lerp(0.92, 0.55, get("furrow_depth")).graph())
    g.add("hanging", "dirmotionblur", {"input1": "furrows"}, intensity=2.0, mblurangle=0.25)

    # ---- flakes ------------------------------------------------------------------------------
    g.add("cracks_src", "cells_3", seed=104, scale=6, disorder=0.6, width=0.05)
    g.add("cracks", "transformation", {"input1": "cracks_src"}, matrix22=(2.0, 0.0, 0.0, 1.0))
    g.add("crumbs", "bnw_spots_2", seed=105, scale=6.0)
    g.add("flaky", "blend", {"source": "crumbs", "destination": "cracks"},
          blendingmode=MULTIPLY, opacitymult=0.5)
    g.add("h_flakes", "blend", {"source": "flaky", "destination": "hanging", "opacity": "hanging"},
          blendingmode=MULTIPLY, opacitymult=0.4)
    g.bind("h_flakes", "opacitymult", lerp(0.0, 0.8, get("flakiness")).graph())
    g.add("fibre_src", "wood_fibers_1", seed=106, scale=10.0)
    g.add("h_fibres", "blend", {"source": "fibre_src", "destination": "h_flakes"},
          blendingmode=ADD_SUB, opacitymult=0.06)
    g.add("height", "histogram_range", {"input": "h_fibres"}, range=1.0, position=0.5)
    normal_and_ao(g, "height", intensity=8.0, height_depth=0.3, spreading=0.15)

    # ---- colour ------------------------------------------------------------------------------
    g.add("bark_base", "uniform", outputcolor=(0.44, 0.37, 0.29, 1.0))
    g.bind("bark_base", "outputcolor", vector(get("bark_color", 3), 1.0).graph())
    g.add("clouds", "clouds_2", seed=107, scale=3.0)
    gradient_over(g, "clouded", "cloud_tones", "clouds", CLOUD_TONES, "bark_base", blendingmode=SOFT_LIGHT,
                  opacitymult=0.7)
    g.add("tops", "histogram_scan", {"input_1": "height"}, position=0.3, contrast=0.4)
    color_over(g, "weathered", "weather_color", (*WEATHER_COLOR, 1.0), "clouded", mask="tops", blendingmode=COPY,
               opacitymult=0.35)
    g.add("lichen_zone", "histogram_select", {"input": "height"}, position=0.4, range=0.15, contrast=0.3)
    g.add("lichen_mask", "blend", {"source": "crumbs", "destination": "lichen_zone"},
          blendingmode=MULTIPLY, opacitymult=1.0)
    color_over(g, "lichened", "lichen_color", (*LICHEN_COLOR, 1.0), "weathered", mask="lichen_mask", blendingmode=COPY,
               opacitymult=0.3)
    g.bind("lichened", "opacitymult", get("lichen").graph())
    gradient_over(g, "deepened", "depth_tones", "height", DEPTH_TONES, "lichened", blendingmode=MULTIPLY,
                  opacitymult=0.85)
    ao_darken(g, "basecolor", "deepened", floor=0.2, opacitymult=0.5)

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_base", "histogram_range", {"input": "crumbs"}, range=0.12, position=0.88)
    g.bind("rough_base", "position", get("roughness").graph())
    g.add("roughness", "blend", {"source": "tops", "destination": "rough_base"},
          blendingmode=SUBTRACT, opacitymult=0.05)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "wood"

SAMPLE_RANGES = {
    "exposed.bark_color": ((0.40, 0.31, 0.21), (0.54, 0.41, 0.31)),
    "exposed.furrow_depth": (0.3, 0.9),
    "exposed.flakiness": (0.1, 0.9),
    "exposed.lichen": (0.0, 0.4),
    "exposed.roughness": (0.75, 0.98),
    "cells.disorder": (0.5, 1.0),
    "plates.intensity": (0.2, 1.0),
    "relief.opacitymult": (0.4, 0.9),
    "hanging.intensity": (0.5, 3.0),
    "h_fibres.opacitymult": (0.02, 0.08),
    "fibre_src.scale": (8.0, 14.0),
    "normal.intensity": (5.0, 12.0),
    "clouded.opacitymult": (0.3, 1.0),
    "weathered.opacitymult": (0.1, 0.5),
    "depth_tones.colors": keys_near(DEPTH_TONES, 0.03),
    "cloud_tones.colors": keys_near(CLOUD_TONES, 0.03),
    "weather_color.outputcolor": rgba_near(WEATHER_COLOR, 0.04),
    "lichen_color.outputcolor": rgba_near(LICHEN_COLOR, 0.04),
}
