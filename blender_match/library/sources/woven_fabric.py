"""Woven fabric: a plain-weave cotton/linen cloth (canvas, chambray) with fibrous threads.

Structure
- Threads: two Weave Generators with one seed, one keeping only the weft (horizontal threads,
  vertical width 0) and one only the warp (vertical threads), each with per-thread luminance
  randomness; where each passes over the other comes from their rounded over/under profiles.
- Fibres: an Anisotropic Noise along the weft, and the same noise turned a quarter turn
  (transformation with an integer matrix, so it tiles) along the warp, multiplied into their
  threads; the cloth height is the maximum of the two fibred thread sets, plus a little fuzz.
- Which thread is on top: the weft minus the warp, thresholded (histogram scan).
- Colour: the exposed warp and weft colours picked by the on-top mask (chambray or plain cloth),
  darkened in the gaps between threads and along the fibres, slight per-thread slub variation.
- Normal from the height (OpenGL) combined with a fuzz detail normal; ambient occlusion.
- Roughness: matte (around the exposed roughness), gaps rougher. Metallic 0.

Exposed parameters
- ``warp_color`` (float3): colour of the vertical threads.
- ``weft_color`` (float3): colour of the horizontal threads.
- ``thread_relief``: how deep the threads stand out (normal intensity and gap darkening).
- ``fuzz``: loose-fibre fuzz on the surface (opacity of a fine noise in height and colour).
- ``roughness``: the cloth's mean roughness.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD_SUB,
    COPY,
    MAX,
    MULTIPLY,
    OUR_OCCLUSION,
    SOFT_LIGHT,
    SUBTRACT,
    ao_darken,
    constant_map,
    gradient_over,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("woven_fabric")
    g.expose("warp_color", (0.20, 0.28, 0.42), min=0.0, max=1.0)
    g.expose("weft_color", (0.78, 0.76, 0.70), min=0.0, max=1.0)
    g.expose("thread_relief", 0.5, min=0.0, max=1.0)
    g.expose("fuzz", 0.35, min=0.0, max=1.0)
    g.expose("roughness", 0.82, min=0.4, max=1.0)

    # ---- threads -----------------------------------------------------------------------------
    g.add("weft", "weave_generator", seed=51, tiling=24, width=(0.0, 0.82), luminance_random=0.25)
    g.add("warp", "weave_generator", seed=51, tiling=24, width=(0.82, 0.0), luminance_random=0.25)
    g.add("fibres_h", "anisotropic_noise", seed=52, x_amount=8, y_amount=256, smoothness=0.4)
    g.add("fibres_src", "anisotropic_noise", seed=53, x_amount=8, y_amount=256, smoothness=0.4)
    g.add("fibres_v", "transformation", {"input1": "fibres_src"}, matrix22=(0.0, 1.0, -1.0, 0.0))
    g.add("weft_fibred", "blend", {"source": "fibres_h", "destination": "weft"},
          blendingmode=MULTIPLY, opacitymult=0.3)
    g.add("warp_fibred", "blend", {"source": "fibres_v", "destination": "warp"},
          blendingmode=MULTIPLY, opacitymult=0.3)
    g.add("cloth", "blend", {"source": "weft_fibred", "destination": "warp_fibred"},
          blendingmode=MAX, opacitymult=1.0)
    g.add("weft_minus_warp", "blend", {"source": "warp", "destination": "weft"},
          blendingmode=SUBTRACT, opacitymult=1.0)
    g.add("weft_top", "histogram_scan", {"input_1": "weft_minus_warp"}, position=0.97, contrast=0.85)

    # ---- fuzz and height ---------------------------------------------------------------------
    g.add("fuzz_noise", "gaussian_noise", seed=54, scale=16.0)
    g.add("fuzz_soft", "blur", {"input1": "fuzz_noise"}, intensity=0.5)
    g.add("fuzzed", "blend", {"source": "fuzz_soft", "destination": "cloth"},
          blendingmode=ADD_SUB, opacitymult=0.1)
    g.bind("fuzzed", "opacitymult", lerp(0.0, 0.25, get("fuzz")).graph())
    g.add("height", "histogram_range", {"input": "fuzzed"}, range=1.0, position=0.5)
    g.add("normal_main", "normal", {"input1": "height"}, intensity=4.0, inversedy=True)
    g.bind("normal_main", "intensity", lerp(1.0, 8.0, get("thread_relief")).graph())
    g.add("normal_fuzz", "normal", {"input1": "fuzz_soft"}, intensity=0.3, inversedy=True)
    g.add("normal", "normal_combine", {"input": "normal_main", "input_1": "normal_fuzz"})
    g.add("ao", "ambient_occlusion_2", {"source": "height"}, height_depth=0.12, spreading=0.06,
          model=OUR_OCCLUSION)

    # ---- colour ------------------------------------------------------------------------------
    g.add("warp_base", "uniform", outputcolor=(0.20, 0.28, 0.42, 1.0))
    g.bind("warp_base", "outputcolor", vector(get("warp_color", 3), 1.0).graph())
    g.add("weft_base", "uniform", outputcolor=(0.78, 0.76, 0.70, 1.0))
    g.bind("weft_base", "outputcolor", vector(get("weft_color", 3), 1.0).graph())
    g.add("threads", "blend", {"source": "weft_base", "destination": "warp_base", "opacity": "weft_top"},
          blendingmode=COPY, opacitymult=1.0)
    gradient_over(g, "shaded", "shade", "height",
                  [(0.0, (0.25, 0.25, 0.25)), (0.5, (0.80, 0.80, 0.80)), (1.0, (1.0, 1.0, 1.0))], "threads",
                  blendingmode=MULTIPLY, opacitymult=0.6)
    g.bind("shaded", "opacitymult", lerp(0.3, 0.9, get("thread_relief")).graph())
    gradient_over(g, "fuzz_colored", "fuzz_tone", "fuzz_soft", [(0.0, (0.42, 0.42, 0.42)), (1.0, (0.62, 0.62, 0.62))],
                  "shaded", blendingmode=SOFT_LIGHT, opacitymult=0.5)
    g.bind("fuzz_colored", "opacitymult", lerp(0.1, 0.9, get("fuzz")).graph())
    g.add("slub", "clouds_1", seed=55, scale=6.0)
    gradient_over(g, "slubbed", "slub_tone", "slub", [(0.0, (0.44, 0.44, 0.44)), (1.0, (0.58, 0.57, 0.55))],
                  "fuzz_colored", blendingmode=SOFT_LIGHT, opacitymult=0.5)
    ao_darken(g, "basecolor", "slubbed", floor=0.3, opacitymult=0.4)

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_inv", "invert_grayscale", {"source": "height"})
    g.add("roughness", "histogram_range", {"input": "rough_inv"}, range=0.15, position=0.82)
    g.bind("roughness", "position", get("roughness").graph())
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "fabric"

SAMPLE_RANGES = {
    "exposed.warp_color": ((0.08, 0.08, 0.10), (0.80, 0.75, 0.70)),
    "exposed.weft_color": ((0.35, 0.33, 0.30), (0.90, 0.88, 0.84)),
    "exposed.thread_relief": (0.2, 0.9),
    "exposed.fuzz": (0.0, 0.8),
    "exposed.roughness": (0.7, 0.95),
    "weft.width": ((0.0, 0.6), (0.0, 0.95)),
    "warp.width": ((0.6, 0.0), (0.95, 0.0)),
    "weft.luminance_random": (0.0, 0.5),
    "warp.luminance_random": (0.0, 0.5),
    "weft_fibred.opacitymult": (0.1, 0.5),
    "warp_fibred.opacitymult": (0.1, 0.5),
    "slubbed.opacitymult": (0.2, 0.8),
}
