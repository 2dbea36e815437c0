"""Varnished wood: a finished hardwood surface (a table top, a veneered panel, a floor board seen
close) under a clear glossy coat.

Structure
- Grain: flat-sawn growth lines, long streaks of two Anisotropic Noises (a coarse and a fine
  one, mixed by the grain density) made wavy by a cloud-driven directional warp and sharpened by
  a histogram scan into latewood lines; fine fibres (Anisotropic Noise) along the same direction,
  and open pores, short dashes (a sparse scan of a finer Anisotropic Noise). Everything runs along u,
  as the library's brushed metal does.
- Colour: the grain picks between a light and a dark tone of the exposed wood colour (from blond
  to walnut, reddened by the stain towards mahogany); the fibres streak it; the pores darker
  still; a cloud noise gives the board's slow variation of tone.
- Height: the varnish levels the surface, so the relief is shallow: the pores a little sunk and
  the latewood lines a hair lower than the earlywood; normal from it (OpenGL, inverted Y), faint
  (``relief`` 0.08 by default, sampled up to 0.25). The flash's highlight lies on the coat, not
  on the wood, so on a real board it is one clean spot with the grain seen through it; a deeper
  relief under a low roughness broke it into a glitter of pores.
- Roughness: the coat's, low and almost even; the pores, which the varnish fills less, a little
  rougher. Metallic 0.

Exposed parameters
- ``wood_color`` (float3): the mid tone of the stained wood; light and dark grain derive from it.
- ``grain_contrast``: how much the latewood lines and pores stand out.
- ``grain_density``: how close the growth lines are (the share of the fine streaks).
- ``roughness``: the varnish's roughness (gloss).
- ``relief``: how much grain and pores show through the coat (normal intensity).
"""
from __future__ import annotations

from blender_match.library.authoring import (
    COPY,
    MULTIPLY,
    SOFT_LIGHT,
    color_over,
    dielectric_tail,
    gradient_over,
    grain_tones,
)
from blender_match.library.expressions import const, get, lerp, vector
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("varnished_wood")
    g.expose("wood_color", (0.42, 0.22, 0.10), min=0.0, max=1.0)
    g.expose("grain_contrast", 0.55, min=0.0, max=1.0)
    g.expose("grain_density", 0.5, min=0.0, max=1.0)
    g.expose("roughness", 0.25, min=0.03, max=0.8)
    g.expose("relief", 0.08, min=0.0, max=1.0)
    g.expose("stain", 0.3, min=0.0, max=1.0)

    # ---- grain -----------------------------------------------------------------------------------
    g.add("lines_coarse", "anisotropic_noise", seed=21, x_amount=3, y_amount=64, smoothness=0.6)
    g.add("lines_fine", "anisotropic_noise", seed=25, x_amount=4, y_amount=192, smoothness=0.5)
    g.add("lines", "blend", {"source": "lines_fine", "destination": "lines_coarse"},
          blendingmode=COPY, opacitymult=0.5)
    g.bind("lines", "opacitymult", get("grain_density").graph())
    g.add("clouds", "clouds_2", seed=22, scale=2.0)
    g.add("lines_wavy", "directionalwarp", {"input1": "lines", "inputintensity": "clouds"},
          intensity=2.0, warpangle=0.25)
    g.add("rings_sharp", "histogram_scan", {"input_1": "lines_wavy"}, position=0.7, contrast=0.6)
    g.add("fibres", "anisotropic_noise", seed=23, x_amount=6, y_amount=256, smoothness=0.2)
    g.add("grain", "contrast_luminosity_grayscale", {"input": "rings_sharp"}, contrast=0.3, luminosity=0.0)
    g.bind("grain", "contrast", lerp(-0.3, 0.8, get("grain_contrast")).graph())
    g.add("pore_src", "anisotropic_noise", seed=24, x_amount=48, y_amount=256, smoothness=0.4)
    g.add("pores", "histogram_scan", {"input_1": "pore_src"}, position=0.8, contrast=0.7, invert_position=True)

    # ---- colour ----------------------------------------------------------------------------------
    stain = get("stain")
    wood = get("wood_color", 3) * vector(const(1.0), 1.0 - 0.45 * stain, 1.0 - 0.55 * stain)
    grain_tones(g, "wood", wood, "grain", 0.6, 1.1, (0.25, 0.13, 0.06), (0.46, 0.24, 0.11))
    gradient_over(g, "wood_fibred", "fibre_tone", "fibres", [(0.0, (0.36, 0.36, 0.36)), (1.0, (0.62, 0.61, 0.60))],
                  "wood_base", blendingmode=SOFT_LIGHT, opacitymult=0.7)
    gradient_over(g, "wood_clouded", "cloud_tone", "clouds", [(0.0, (0.42, 0.42, 0.42)), (1.0, (0.58, 0.56, 0.53))],
                  "wood_fibred", blendingmode=SOFT_LIGHT, opacitymult=0.5)
    color_over(g, "basecolor", "pore_color", (0.35, 0.30, 0.27, 1.0), "wood_clouded", mask="pores",
               blendingmode=MULTIPLY, opacitymult=0.6)
    g.bind("basecolor", "opacitymult", lerp(0.15, 0.7, get("grain_contrast")).graph())

    # ---- height ----------------------------------------------------------------------------------
    g.add("height_grain", "histogram_range", {"input": "grain"}, range=0.3, position=0.6)
    g.add("pore_depth", "uniform", colorswitch=False, outputcolor=(0.0, 0.0, 0.0, 1.0))
    g.add("height", "blend", {"source": "pore_depth", "destination": "height_grain", "opacity": "pores"},
          blendingmode=COPY, opacitymult=0.15)

    # ---- normal, roughness and metallic ----------------------------------------------------------
    dielectric_tail(g, "height", 2.0, lerp(0.0, 5.0, get("relief")), "pores", 0.1, 0.18)
    return g


FAMILY = "wood"

SAMPLE_TOGETHER = ("exposed.wood_color",)  # a line from dark walnut to blond; the stain reddens it

SAMPLE_RANGES = {
    "exposed.wood_color": ((0.14, 0.07, 0.03), (0.8, 0.56, 0.34)),
    "exposed.stain": (0.0, 1.0),
    "exposed.grain_contrast": (0.2, 0.95),
    "exposed.grain_density": (0.1, 1.0),
    "exposed.roughness": (0.1, 0.5),
    "exposed.relief": (0.0, 0.25),
    "lines_wavy.intensity": (0.5, 6.0),
    "wood_fibred.opacitymult": (0.3, 1.0),
    "rings_sharp.position": (0.55, 0.85),
    "rings_sharp.contrast": (0.3, 0.8),
    "clouds.scale": (1.0, 4.0),
    "wood_clouded.opacitymult": (0.2, 0.8),
    "pores.position": (0.7, 0.95),
}
