"""Material: denim, a 2/1 twill with steep diagonal ribs, dyed warp over a pale weft, faded.

Structure
- Twill ribs: in a 2/1 twill every warp thread floats over two weft threads and under one, the
  float stepping one thread each row, so the surface shows steep diagonal ribs of warp (about 63
  degrees, rising to the right as right-hand twill). They are a slanted Stripes generator (24 ribs,
  shift 12: integer, so it tiles) two thirds wide, repeated twice each way (integer matrix): 48
  ribs across, the warp-on-top mask.
- Threads: vertical and horizontal Stripes (144 warp and 112 weft threads: the generator's
  count repeated by integer matrices, the weft turned a quarter turn) give the rounded warp and
  weft threads; the warp is multiplied by the ring-spun
  unevenness (a vertical anisotropic noise, one streak per few threads), which makes denim's
  typical fine vertical streaks.
- Height: the warp floats laid over the lower weft through the rib mask (copy blend), plus a
  broad cloud for the cloth not lying perfectly flat. Normal from it (OpenGL), ambient occlusion.
- Colour: the exposed dye colour on the warp, the exposed weft colour (a little tinted by the
  dye, as stray dye and shadow make it) where the weft shows,
  lightened along the ring-spun streaks and on the raised floats; fading (exposed) screens a
  paler, greyed version of the dye over cloudy worn areas, as washed denim loses its indigo.
- Roughness: high (cotton), gaps rougher. Metallic 0.

Exposed parameters
- ``denim_color`` (float3): the warp dye (indigo by default; black, grey or coloured denims).
- ``weft_color`` (float3): the undyed/pale weft showing between the ribs.
- ``fade``: how washed-out and worn the dye is (cloudy faded areas, paler rib tops).
- ``twill_depth``: relief of the ribs (normal intensity and shading).
- ``roughness``: the cloth's mean roughness.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD_SUB,
    COPY,
    MULTIPLY,
    SCREEN,
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


def build() -> SbsGraph:
    g = SbsGraph("denim")
    g.expose("denim_color", (0.10, 0.16, 0.32), min=0.0, max=1.0)
    g.expose("weft_color", (0.78, 0.77, 0.72), min=0.0, max=1.0)
    g.expose("fade", 0.35, min=0.0, max=1.0)
    g.expose("twill_depth", 0.5, min=0.0, max=1.0)
    g.expose("roughness", 0.85, min=0.5, max=1.0)

    # ---- weave ---------------------------------------------------------------------------------
    g.add("ribs_src", "stripes", number=24, shift=12, width=0.72, softness=0.6)
    g.add("ribs", "transformation", {"input1": "ribs_src"}, matrix22=(2.0, 0.0, 0.0, 2.0))
    g.add("warp_src", "stripes", number=48, width=0.8, softness=0.9)
    g.add("warp_threads", "transformation", {"input1": "warp_src"}, matrix22=(3.0, 0.0, 0.0, 3.0))
    g.add("weft_src", "stripes", number=56, width=0.8, softness=0.9)
    g.add("weft_threads", "transformation", {"input1": "weft_src"}, matrix22=(0.0, 2.0, -2.0, 0.0))
    g.add("ring_src", "anisotropic_noise", seed=71, x_amount=6, y_amount=64, smoothness=0.6)
    g.add("ring", "transformation", {"input1": "ring_src"}, matrix22=(0.0, 1.0, -1.0, 0.0))
    g.add("warp_uneven", "blend", {"source": "ring", "destination": "warp_threads"},
          blendingmode=MULTIPLY, opacitymult=0.35)
    g.add("warp_level", "histogram_range", {"input": "warp_uneven"}, range=0.55, position=0.68)
    g.add("weft_level", "histogram_range", {"input": "weft_threads"}, range=0.4, position=0.3)
    g.add("woven", "blend", {"source": "warp_level", "destination": "weft_level", "opacity": "ribs"},
          blendingmode=COPY, opacitymult=1.0)
    g.add("lie", "clouds_2", seed=72, scale=2.0)
    g.add("lying", "blend", {"source": "lie", "destination": "woven"}, blendingmode=ADD_SUB, opacitymult=0.06)
    g.add("height", "histogram_range", {"input": "lying"}, range=1.0, position=0.5)
    normal_and_ao(g, "height", intensity=3.0, height_depth=0.1, spreading=0.04)
    g.bind("normal", "intensity", lerp(0.5, 7.0, get("twill_depth")).graph())

    # ---- colour --------------------------------------------------------------------------------
    g.add("dye", "uniform", outputcolor=(0.10, 0.16, 0.32, 1.0))
    g.bind("dye", "outputcolor", vector(get("denim_color", 3), 1.0).graph())
    g.add("weft_base", "uniform", outputcolor=(0.78, 0.77, 0.72, 1.0))
    g.bind("weft_base", "outputcolor", vector(get("weft_color", 3), 1.0).graph())
    gradient_over(g, "dye_streaked", "streak_tone", "ring", [(0.0, (0.38, 0.38, 0.38)), (1.0, (0.66, 0.66, 0.66))],
                  "dye", blendingmode=SOFT_LIGHT, opacitymult=0.8)
    g.add("weft_tinted", "blend", {"source": "dye", "destination": "weft_base"},
          blendingmode=MULTIPLY, opacitymult=0.45)
    g.add("threads", "blend", {"source": "dye_streaked", "destination": "weft_tinted", "opacity": "ribs"},
          blendingmode=COPY, opacitymult=1.0)
    # fading: a paler, greyer dye screened over cloudy worn areas and the raised floats
    g.add("wash", "clouds_2", seed=73, scale=3.0)
    g.add("speck", "bnw_spots_3", seed=74, scale=6.0)
    g.add("wash_speck", "blend", {"source": "speck", "destination": "wash"}, blendingmode=SOFT_LIGHT, opacitymult=0.6)
    g.add("wash_streak", "blend", {"source": "ring", "destination": "wash_speck"},
          blendingmode=SOFT_LIGHT, opacitymult=0.8)
    g.add("tops", "blend", {"source": "height", "destination": "wash_streak"}, blendingmode=MULTIPLY, opacitymult=0.5)
    g.add("worn", "histogram_scan", {"input_1": "tops"}, position=0.45, contrast=0.05)
    g.bind("worn", "position", lerp(0.05, 0.85, get("fade")).graph())
    color_over(g, "faded", "fade_color", (0.45, 0.46, 0.48, 1.0), "threads", mask="worn", blendingmode=SCREEN,
               opacitymult=0.7)
    g.bind("faded", "opacitymult", lerp(0.1, 0.6, get("fade")).graph())
    gradient_over(g, "shaded", "shade", "height",
                  [(0.0, (0.35, 0.35, 0.35)), (0.5, (0.80, 0.80, 0.80)), (1.0, (1.0, 1.0, 1.0))], "faded",
                  blendingmode=MULTIPLY, opacitymult=0.5)
    g.bind("shaded", "opacitymult", lerp(0.2, 0.8, get("twill_depth")).graph())
    ao_darken(g, "basecolor", "shaded", floor=0.35, opacitymult=0.4)

    # ---- roughness and metallic ------------------------------------------------------------------
    g.add("rough_inv", "invert_grayscale", {"source": "height"})
    g.add("roughness", "histogram_range", {"input": "rough_inv"}, range=0.12, position=0.85)
    g.bind("roughness", "position", get("roughness").graph())
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "fabric"

SAMPLE_RANGES = {
    # indigo (dark to mid), black, grey, and coloured denims
    "exposed.denim_color": ((0.03, 0.03, 0.05), (0.60, 0.50, 0.55)),
    "exposed.weft_color": ((0.55, 0.53, 0.48), (0.90, 0.89, 0.85)),
    "exposed.fade": (0.0, 0.6),
    "exposed.twill_depth": (0.25, 0.85),
    "exposed.roughness": (0.75, 0.95),
    "ribs_src.width": (0.62, 0.8),
    "ribs_src.softness": (0.3, 0.7),
    "warp_uneven.opacitymult": (0.15, 0.55),
    "dye_streaked.opacitymult": (0.4, 1.0),
    "lying.opacitymult": (0.0, 0.12),
    "weft_tinted.opacitymult": (0.2, 0.7),
    "fade_color.outputcolor": ((0.35, 0.35, 0.36, 1.0), (0.55, 0.56, 0.60, 1.0)),
}
