"""Cardboard: corrugated cardboard / kraft paper liner with paper fibres, faint flute ribs, specks and creases.

Structure
- Flute ribs: a Stripes generator (about 36 flutes on a ~30 cm sample, so the 8 mm pitch of a
  common C flute) with soft edges, turned a quarter turn (integer matrix: it tiles) so the flutes
  run across the sample as in the photos, warped a little by clouds so the liner does not look machined;
  they only show as a faint relief and faint banding through the liner (exposed rib depth).
- Fibres: short paper fibres are white noise smeared by a short directional blur along the machine
  direction, plus a second one across it at a lower weight; a BnW Spots 3 mottle gives the cloudy
  formation of kraft paper.
- Specks: dark bits of bark and recycled ink, the brightest few percent of a fine BnW Spots 3
  (exposed specks). (Blurred white noise was tried: below 256 px the white noise is remapped to
  a uniform histogram after the blur's scale is lost, so its thresholded specks covered 15 % of
  a 128 px render and 0.6 % of a 256 px one.)
- Creases: a few long, nearly straight fold lines (a sparse Scratches Generator, widened by a
  blur) and a few finer scuffs (a second one), pressed into the height and darkened (exposed
  creases). (The Creased generator gave a cell-like web of lines that read as cracked mud.)
- Height: ribs + fibres + mottle - creases. Normal from it (OpenGL) with a fibre detail normal.
- Colour: the exposed paper colour, mottled, fibre-streaked, slightly lighter on the rib crests,
  specks and darkened creases.
- Roughness: paper is very matte (around the exposed roughness), creases a touch smoother
  (compressed fibres). Metallic 0.

Exposed parameters
- ``paper_color`` (float3): kraft brown by default; bleached, gray recycled and white-top liners too.
- ``rib_depth``: how much the flutes show through the liner (relief and banding).
- ``creases``: depth and darkness of the creases and scuffs.
- ``specks``: amount of dark specks.
- ``roughness``: mean roughness.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD_SUB,
    MAX,
    MULTIPLY,
    OUR_OCCLUSION,
    OVERLAY,
    SOFT_LIGHT,
    SUBTRACT,
    ao_darken,
    color_over,
    constant_map,
    gradient_over,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("cardboard")
    g.expose("paper_color", (0.56, 0.43, 0.30), min=0.0, max=1.0)
    g.expose("rib_depth", 0.4, min=0.0, max=1.0)
    g.expose("creases", 0.25, min=0.0, max=1.0)
    g.expose("specks", 0.4, min=0.0, max=1.0)
    g.expose("roughness", 0.85, min=0.4, max=1.0)

    # ---- flute ribs --------------------------------------------------------------------------
    g.add("stripes", "stripes", number=36, width=0.5, softness=1.0)
    g.add("stripes_h", "transformation", {"input1": "stripes"}, matrix22=(0.0, 1.0, -1.0, 0.0))
    g.add("rib_noise", "clouds_1", seed=91, scale=2.0)
    g.add("ribs_warp", "warp", {"input1": "stripes_h", "inputgradient": "rib_noise"}, intensity=0.006)
    g.add("ribs", "blur_hq_grayscale", {"source": "ribs_warp"}, intensity=2.0)

    # ---- fibres and formation ----------------------------------------------------------------
    g.add("noise_a", "white_noise")
    g.add("fibres_along", "dirmotionblur", {"input1": "noise_a"}, intensity=2.0, mblurangle=0.0)
    g.add("noise_b", "white_noise_fast")
    g.add("fibres_across", "dirmotionblur", {"input1": "noise_b"}, intensity=1.5, mblurangle=0.25)
    g.add("fibres", "blend", {"source": "fibres_across", "destination": "fibres_along"},
          blendingmode=OVERLAY, opacitymult=0.5)
    g.add("fibres_level", "histogram_range", {"input": "fibres"}, range=1.0, position=0.5)
    g.add("formation", "bnw_spots_3", seed=92, scale=6.0)

    # ---- specks ------------------------------------------------------------------------------
    g.add("speck_noise", "bnw_spots_3", seed=95, scale=32.0)
    g.add("speck_mask", "histogram_scan", {"input_1": "speck_noise"}, position=0.03, contrast=0.85)
    g.bind("speck_mask", "position", lerp(0.002, 0.05, get("specks")).graph())

    # ---- creases and scuffs ------------------------------------------------------------------
    g.add("crease_lines", "scratches_generator", seed=93, amount=1, length=2.0, width=0.012, angle=0.0,
          angle_random=0.6, length_random=0.3, luminance_random=0.2)
    g.add("scuffs", "scratches_generator", seed=94, amount=2, length=1.0, width=0.008, angle=0.1,
          angle_random=0.5, luminance_random=0.6, mask_random=0.5)
    g.add("marks", "blend", {"source": "scuffs", "destination": "crease_lines"},
          blendingmode=MAX, opacitymult=0.6)
    g.add("marks_soft", "blur_hq_grayscale", {"source": "marks"}, intensity=0.6)
    g.add("marks_level", "histogram_range", {"input": "marks_soft"}, range=0.35, position=0.175)
    g.bind("marks_level", "range", lerp(0.0, 0.9, get("creases")).graph())
    g.bind("marks_level", "position", lerp(0.0, 0.45, get("creases")).graph())

    # ---- height ------------------------------------------------------------------------------
    g.add("rib_level", "histogram_range", {"input": "ribs"}, range=0.3, position=0.5)
    g.bind("rib_level", "range", lerp(0.0, 0.6, get("rib_depth")).graph())
    g.add("formed", "blend", {"source": "formation", "destination": "rib_level"},
          blendingmode=ADD_SUB, opacitymult=0.05)
    g.add("fibred", "blend", {"source": "fibres_level", "destination": "formed"},
          blendingmode=ADD_SUB, opacitymult=0.05)
    g.add("pressed", "blend", {"source": "marks_level", "destination": "fibred"},
          blendingmode=SUBTRACT, opacitymult=0.5)
    g.add("height", "histogram_range", {"input": "pressed"}, range=1.0, position=0.5)

    g.add("normal_main", "normal", {"input1": "height"}, intensity=2.0, inversedy=True)
    g.add("normal_fibres", "normal", {"input1": "fibres_along"}, intensity=0.3, inversedy=True)
    g.add("normal", "normal_combine", {"input": "normal_main", "input_1": "normal_fibres"})
    g.add("ao", "ambient_occlusion_2", {"source": "height"}, height_depth=0.06, spreading=0.08,
          model=OUR_OCCLUSION)

    # ---- colour ------------------------------------------------------------------------------
    g.add("base", "uniform", outputcolor=(0.56, 0.43, 0.30, 1.0))
    g.bind("base", "outputcolor", vector(get("paper_color", 3), 1.0).graph())
    gradient_over(g, "formed_color", "formation_tones", "formation",
                  [(0.0, (0.42, 0.42, 0.42)), (1.0, (0.57, 0.56, 0.55))], "base", blendingmode=SOFT_LIGHT,
                  opacitymult=0.6)
    gradient_over(g, "fibred_color", "fibre_tones", "fibres_level",
                  [(0.0, (0.36, 0.35, 0.34)), (1.0, (0.66, 0.65, 0.62))], "formed_color", blendingmode=SOFT_LIGHT,
                  opacitymult=0.5)
    gradient_over(g, "banded", "rib_tones", "ribs", [(0.0, (0.40, 0.40, 0.40)), (1.0, (0.58, 0.58, 0.57))],
                  "fibred_color", blendingmode=SOFT_LIGHT, opacitymult=0.4)
    g.bind("banded", "opacitymult", lerp(0.0, 1.0, get("rib_depth")).graph())
    color_over(g, "specked", "speck_color", (0.13, 0.10, 0.08, 1.0), "banded", mask="speck_mask", blendingmode=MULTIPLY,
               opacitymult=0.6)
    gradient_over(g, "marked", "mark_tones", "marks_soft", [(0.0, (1.0, 1.0, 1.0)), (1.0, (0.45, 0.42, 0.40))],
                  "specked", blendingmode=MULTIPLY, opacitymult=0.4)
    g.bind("marked", "opacitymult", lerp(0.0, 0.8, get("creases")).graph())
    ao_darken(g, "basecolor", "marked", floor=0.4, opacitymult=0.3)

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_base", "histogram_range", {"input": "fibres_level"}, range=0.08, position=0.85)
    g.bind("rough_base", "position", get("roughness").graph())
    g.add("roughness", "blend", {"source": "marks_soft", "destination": "rough_base"},
          blendingmode=SUBTRACT, opacitymult=0.1)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "ground"

SAMPLE_RANGES = {
    "exposed.paper_color": ((0.46, 0.35, 0.24), (0.72, 0.58, 0.45)),
    "exposed.rib_depth": (0.1, 0.8),
    "exposed.creases": (0.0, 0.8),
    "exposed.specks": (0.1, 0.9),
    "exposed.roughness": (0.7, 0.95),
    "ribs_warp.intensity": (0.0, 0.012),
    "ribs.intensity": (1.0, 3.0),
    "fibres_along.intensity": (1.0, 3.5),
    "formed.opacitymult": (0.02, 0.12),
    "formed_color.opacitymult": (0.3, 0.9),
    "fibred_color.opacitymult": (0.2, 0.8),
    "normal_main.intensity": (1.0, 3.5),
    # fine-scale filters stay fine (the default +-15% of their full range would smear the fibres
    # into hatching and the specks into blots), the fibres keep the machine direction
    "normal_fibres.intensity": (0.1, 0.6),
    "speck_noise.scale": (24.0, 32.0),
    "fibres_across.intensity": (0.8, 2.5),
    "fibres_across.mblurangle": (0.25, 0.25),
    "fibres_along.mblurangle": (0.0, 0.0),
    "formation.scale": (4.0, 9.0),
    "marks_soft.intensity": (0.3, 1.2),
    "crease_lines.width": (0.006, 0.02),
    "scuffs.width": (0.004, 0.012),
    # the flutes stay straight
    "stripes.width": (0.5, 0.5),
    "stripes.softness": (1.0, 1.0),
}
