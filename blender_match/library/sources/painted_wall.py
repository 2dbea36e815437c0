"""Painted wall: roller-applied matte or eggshell paint over drywall or smooth plaster, with its orange-peel stipple.

Structure
- Stipple: the roller's orange peel, soft round pits and bumps a few millimetres across (a fine
  Perlin noise, its crests rounded by a second, finer one), gently undulated by a cloud noise
  (the coat's uneven thickness), with a faint grain of the filler under it.
- Specks: a few grains of dust caught in the coat, sparse dots from white noise, dark and a
  little proud.
- Colour: the exposed paint colour, a touch lighter on the stipple's crests (the roller leaves
  more pigment there) and mottled very slightly by the clouds; the specks darker.
- Height: the stipple plus the undulation; normal from it (OpenGL, inverted Y).
- Roughness: the paint's sheen (matte to eggshell), the stipple's crests a little rougher than
  its pits. Metallic 0.

Exposed parameters
- ``paint_color`` (float3): the paint colour.
- ``stipple``: depth of the orange peel (normal intensity).
- ``stipple_size``: the size of the stipple's pits and bumps (Perlin scale, larger = finer).
- ``roughness``: the paint's sheen.
- ``specks``: how many dust specks.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD_SUB,
    MULTIPLY,
    SOFT_LIGHT,
    color_over,
    dielectric_tail,
    gradient_over,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("painted_wall")
    g.expose("paint_color", (0.86, 0.85, 0.82), min=0.0, max=1.0)
    g.expose("stipple", 0.4, min=0.0, max=1.0)
    g.expose("stipple_size", 0.5, min=0.0, max=1.0)
    g.expose("roughness", 0.75, min=0.3, max=1.0)
    g.expose("specks", 0.3, min=0.0, max=1.0)

    # ---- stipple ---------------------------------------------------------------------------------
    g.add("peel", "perlin_noise", seed=41, scale=48.0)
    g.bind("peel", "scale", lerp(24.0, 96.0, get("stipple_size")).graph())
    g.add("peel_fine", "perlin_noise", seed=42, scale=128.0)
    g.add("peel_rounded", "blend", {"source": "peel_fine", "destination": "peel"},
          blendingmode=ADD_SUB, opacitymult=0.25)
    g.add("coat", "clouds_2", seed=43, scale=3.0)
    g.add("peel_undulated", "blend", {"source": "coat", "destination": "peel_rounded"},
          blendingmode=ADD_SUB, opacitymult=0.2)
    g.add("filler", "white_noise", seed=44)
    g.add("stipple_all", "blend", {"source": "filler", "destination": "peel_undulated"},
          blendingmode=ADD_SUB, opacitymult=0.04)

    # ---- specks ----------------------------------------------------------------------------------
    g.add("speck_noise", "white_noise", seed=45)
    g.add("speck_dots", "histogram_scan", {"input_1": "speck_noise"}, contrast=0.9)
    g.bind("speck_dots", "position", lerp(0.0, 0.004, get("specks")).graph())

    # ---- colour ----------------------------------------------------------------------------------
    g.add("paint", "uniform", outputcolor=(0.86, 0.85, 0.82, 1.0))
    g.bind("paint", "outputcolor", vector(get("paint_color", 3), 1.0).graph())
    gradient_over(g, "paint_crests", "crest_tone", "peel_rounded",
                  [(0.0, (0.45, 0.45, 0.45)), (1.0, (0.55, 0.55, 0.55))], "paint", blendingmode=SOFT_LIGHT,
                  opacitymult=0.6)
    gradient_over(g, "paint_mottled", "mottle_tone", "coat", [(0.0, (0.47, 0.47, 0.47)), (1.0, (0.53, 0.53, 0.53))],
                  "paint_crests", blendingmode=SOFT_LIGHT, opacitymult=0.5)
    color_over(g, "basecolor", "speck_color", (0.25, 0.23, 0.21, 1.0), "paint_mottled", mask="speck_dots",
               blendingmode=MULTIPLY, opacitymult=0.8)

    # ---- height ----------------------------------------------------------------------------------
    g.add("height_stipple", "histogram_range", {"input": "stipple_all"}, range=0.5, position=0.5)
    g.add("height", "blend", {"source": "speck_dots", "destination": "height_stipple"},
          blendingmode=ADD_SUB, opacitymult=0.3)

    # ---- normal, roughness and metallic ----------------------------------------------------------
    dielectric_tail(g, "height", 1.5, lerp(0.0, 4.0, get("stipple")), "peel_rounded", 0.08, 0.75)
    return g


FAMILY = "plaster"

SAMPLE_RANGES = {
    "exposed.paint_color": ((0.45, 0.45, 0.43), (0.95, 0.95, 0.94)),
    "exposed.stipple": (0.1, 0.8),
    "exposed.stipple_size": (0.0, 1.0),
    "exposed.roughness": (0.45, 0.95),
    "exposed.specks": (0.0, 0.8),
    "coat.scale": (1.5, 5.0),
    "peel_undulated.opacitymult": (0.05, 0.4),
    "paint_crests.opacitymult": (0.2, 0.9),
}
