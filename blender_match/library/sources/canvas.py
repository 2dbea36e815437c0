"""Material: plain-weave canvas or linen: coarse crossing threads with slubs, natural beige by default.

Structure
- Threads: two Weave Generators with one seed (40 threads each way, wider and more tightly packed
  than a shirting cloth), one keeping only the weft and one only the warp; their rounded
  over/under profiles give the plain-weave crossing.
- Slubs: canvas and linen yarns are uneven, thick and thin along their length. Long, per-thread
  streaks of an Anisotropic Noise (a few cells along, one row per thread) multiply each thread
  set; the horizontal one is turned a quarter turn (integer matrix, tiles) for the warp. A
  histogram scan then thresholds the profile, so a thick stretch is also wider, not only higher.
- Fibres: a fine anisotropic noise along each direction multiplied in (the spun fibres).
- The cloth (maximum of the two thread sets) is slightly warped by a soft cloud, so the threads
  are not ruler-straight, and a broad cloud adds unevenness.
- Height -> normal (OpenGL) and ambient occlusion (the gaps between threads).
- Colour: the exposed canvas colour, lighter on the thick slubs and thread tops, darker in the
  gaps, with scattered dark flecks (the neps and bits of straw of unbleached linen and cotton,
  exposed amount) and a soft cloudy variation.
- Roughness: very matte, gaps rougher. Metallic 0.

Exposed parameters
- ``canvas_color`` (float3): the cloth colour (unbleached beige by default; any dye).
- ``slubs``: how irregular the yarn is (slub strength in the threads' height and width).
- ``thread_relief``: how deep the weave is (normal intensity, gap shading).
- ``flecks``: amount of dark neps/specks in the cloth.
- ``roughness``: the cloth's mean roughness.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD_SUB,
    MAX,
    MULTIPLY,
    SOFT_LIGHT,
    ao_darken,
    color_over,
    constant_map,
    gradient_over,
    normal_and_ao,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph

QUARTER_TURN = (0.0, 1.0, -1.0, 0.0)


def build() -> SbsGraph:
    g = SbsGraph("canvas")
    g.expose("canvas_color", (0.72, 0.62, 0.46), min=0.0, max=1.0)
    g.expose("slubs", 0.5, min=0.0, max=1.0)
    g.expose("thread_relief", 0.55, min=0.0, max=1.0)
    g.expose("flecks", 0.3, min=0.0, max=1.0)
    g.expose("roughness", 0.9, min=0.5, max=1.0)

    # ---- threads ------------------------------------------------------------------------------
    g.add("weft", "weave_generator", seed=91, tiling=20, width=(0.0, 0.92), luminance_random=0.15)
    g.add("warp", "weave_generator", seed=91, tiling=20, width=(0.92, 0.0), luminance_random=0.15)
    g.add("slub_h", "anisotropic_noise", seed=92, x_amount=5, y_amount=40, smoothness=0.8)
    g.add("slub_v_src", "anisotropic_noise", seed=93, x_amount=5, y_amount=40, smoothness=0.8)
    g.add("slub_v", "transformation", {"input1": "slub_v_src"}, matrix22=QUARTER_TURN)
    g.add("weft_slub", "blend", {"source": "slub_h", "destination": "weft"}, blendingmode=MULTIPLY, opacitymult=0.5)
    g.bind("weft_slub", "opacitymult", lerp(0.0, 0.8, get("slubs")).graph())
    g.add("warp_slub", "blend", {"source": "slub_v", "destination": "warp"}, blendingmode=MULTIPLY, opacitymult=0.5)
    g.bind("warp_slub", "opacitymult", lerp(0.0, 0.8, get("slubs")).graph())
    g.add("fib_h", "anisotropic_noise", seed=94, x_amount=16, y_amount=256, smoothness=0.4)
    g.add("fib_v_src", "anisotropic_noise", seed=95, x_amount=16, y_amount=256, smoothness=0.4)
    g.add("fib_v", "transformation", {"input1": "fib_v_src"}, matrix22=QUARTER_TURN)
    g.add("weft_fib", "blend", {"source": "fib_h", "destination": "weft_slub"}, blendingmode=MULTIPLY, opacitymult=0.25)
    g.add("warp_fib", "blend", {"source": "fib_v", "destination": "warp_slub"}, blendingmode=MULTIPLY, opacitymult=0.25)
    g.add("cloth", "blend", {"source": "weft_fib", "destination": "warp_fib"}, blendingmode=MAX, opacitymult=1.0)
    g.add("threads_shaped", "histogram_scan", {"input_1": "cloth"}, position=0.6, contrast=0.2)
    g.add("waver", "clouds_1", seed=96, scale=3.0)
    g.add("wavy", "warp", {"input1": "threads_shaped", "inputgradient": "waver"}, intensity=0.04)
    g.add("lie", "clouds_2", seed=97, scale=2.0)
    g.add("uneven", "blend", {"source": "lie", "destination": "wavy"}, blendingmode=ADD_SUB, opacitymult=0.06)
    g.add("height", "histogram_range", {"input": "uneven"}, range=1.0, position=0.5)
    normal_and_ao(g, "height", intensity=4.0, height_depth=0.12, spreading=0.05)
    g.bind("normal", "intensity", lerp(1.0, 9.0, get("thread_relief")).graph())

    # ---- colour ------------------------------------------------------------------------------
    g.add("base", "uniform", outputcolor=(0.72, 0.62, 0.46, 1.0))
    g.bind("base", "outputcolor", vector(get("canvas_color", 3), 1.0).graph())
    g.add("slub_mix", "blend", {"source": "slub_v", "destination": "slub_h"}, blendingmode=MAX, opacitymult=1.0)
    gradient_over(g, "slubbed", "slub_tone", "slub_mix", [(0.0, (0.44, 0.44, 0.44)), (1.0, (0.58, 0.57, 0.55))], "base",
                  blendingmode=SOFT_LIGHT, opacitymult=0.6)
    gradient_over(g, "clouded", "cloud_tone", "lie", [(0.0, (0.45, 0.45, 0.45)), (1.0, (0.55, 0.55, 0.55))], "slubbed",
                  blendingmode=SOFT_LIGHT, opacitymult=0.6)
    gradient_over(g, "shaded", "shade", "height",
                  [(0.0, (0.25, 0.25, 0.25)), (0.5, (0.80, 0.80, 0.80)), (1.0, (1.0, 1.0, 1.0))], "clouded",
                  blendingmode=MULTIPLY, opacitymult=0.5)
    g.bind("shaded", "opacitymult", lerp(0.2, 0.85, get("thread_relief")).graph())
    g.add("nep_noise", "bnw_spots_3", seed=98, scale=20.0)
    g.add("neps", "histogram_scan", {"input_1": "nep_noise"}, position=0.06, contrast=0.8)
    g.bind("neps", "position", lerp(0.0, 0.1, get("flecks")).graph())
    color_over(g, "flecked", "nep_color", (0.22, 0.17, 0.12, 1.0), "shaded", mask="neps", blendingmode=MULTIPLY,
               opacitymult=0.8)
    ao_darken(g, "basecolor", "flecked", floor=0.3, opacitymult=0.4)

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_inv", "invert_grayscale", {"source": "height"})
    g.add("roughness", "histogram_range", {"input": "rough_inv"}, range=0.12, position=0.9)
    g.bind("roughness", "position", get("roughness").graph())
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "fabric"

SAMPLE_RANGES = {
    # natural linen/cotton beiges and greys, and dyed canvases of any colour
    "exposed.canvas_color": ((0.05, 0.05, 0.05), (0.90, 0.88, 0.82)),
    "exposed.slubs": (0.1, 0.9),
    "exposed.thread_relief": (0.25, 0.85),
    "exposed.flecks": (0.0, 0.7),
    "exposed.roughness": (0.8, 0.97),
    "weft.width": ((0.0, 0.8), (0.0, 0.97)),
    "warp.width": ((0.8, 0.0), (0.97, 0.0)),
    "weft.luminance_random": (0.0, 0.35),
    "warp.luminance_random": (0.0, 0.35),
    "wavy.intensity": (0.0, 0.08),
    "threads_shaped.position": (0.5, 0.7),
    "clouded.opacitymult": (0.2, 0.9),
}
