"""Worn leather: smooth aniline/vintage leather with scuffs, crazed finish, worn patches and creases.

Structure
- Surface: a smooth hide, a very shallow hair-cell grain (Cells 1, fine) on a broad undulation
  (clouds), so the flash highlight breaks up only slightly as on a real aged sofa or jacket.
- Crazing: the fine network of cracks in an aged finish, a thin-cracked Cells 3 pattern warped by
  a noise so the polygons are irregular, kept only in patches (a thresholded cloud mask) because
  finishes craze where they are flexed and dried, not everywhere.
- Creases: thin, meandering, roughly parallel fold lines: a narrow band (histogram select) around
  the mid level of a smoothed directional noise (its contour lines), warped by a broad cloud, blurred,
  and shown only where a second cloud mask lets them (the places that bend).
- Worn patches: a large cloud plus a finer one, softly thresholded by the exposed wear; scuffs: short scratch
  lines (Scratches Generator) shown more with wear.
- Height: undulation + grain - crazing - creases - scuffs; normal from it (OpenGL); ambient
  occlusion from the height.
- Colour: the exposed dye, strongly variegated by clouds (aniline dye soaks unevenly), darker in
  creases and cracks (dirt and dye pool there), lighter, desaturated and warmer in the worn patches
  and scuffs where the top dye is rubbed off.
- Roughness: around the exposed roughness, worn patches and scuffs more matte, creases rougher.
  Metallic 0.

Exposed parameters
- ``leather_color`` (float3): the dye colour (browns by default; any dye).
- ``wear``: how much of the finish is rubbed lighter (worn patch threshold, scuff visibility).
- ``crazing``: depth and darkness of the crazing cracks.
- ``creases``: depth and darkness of the fold creases.
- ``roughness``: mean roughness of the finish.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD,
    ADD_SUB,
    MULTIPLY,
    SCREEN,
    SOFT_LIGHT,
    SUBTRACT,
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
    g = SbsGraph("worn_leather")
    g.expose("leather_color", (0.34, 0.18, 0.09), min=0.0, max=1.0)
    g.expose("wear", 0.45, min=0.0, max=1.0)
    g.expose("crazing", 0.5, min=0.0, max=1.0)
    g.expose("creases", 0.5, min=0.0, max=1.0)
    g.expose("roughness", 0.5, min=0.2, max=0.95)

    # ---- noises and masks --------------------------------------------------------------------
    g.add("flow", "clouds_2", seed=71, scale=3.0)
    g.add("broad", "clouds_1", seed=72, scale=2.0)
    g.add("craze_area_src", "clouds_2", seed=73, scale=2.0)
    g.add("craze_area", "histogram_scan", {"input_1": "craze_area_src"}, position=0.45, contrast=0.3)
    g.add("crease_area_src", "clouds_1", seed=74, scale=3.0)
    g.add("crease_area", "histogram_scan", {"input_1": "crease_area_src"}, position=0.5, contrast=0.5)

    # ---- grain -------------------------------------------------------------------------------
    g.add("grain_cells", "cells_1", seed=75, scale=64, disorder=0.8)
    g.add("grain", "histogram_range", {"input": "grain_cells"}, range=0.06, position=0.5)
    g.add("base", "blend", {"source": "broad", "destination": "grain"},
          blendingmode=ADD_SUB, opacitymult=0.15)

    # ---- crazing -----------------------------------------------------------------------------
    g.add("craze_cells", "cells_3", seed=76, scale=20, disorder=0.9, width=0.05)
    g.add("craze_warp", "warp", {"input1": "craze_cells", "inputgradient": "flow"}, intensity=0.06)
    g.add("craze_lines", "invert_grayscale", {"source": "craze_warp"})
    g.add("craze_masked", "blend", {"source": "craze_area", "destination": "craze_lines"},
          blendingmode=MULTIPLY, opacitymult=1.0)
    g.add("crazed", "blend", {"source": "craze_masked", "destination": "base"},
          blendingmode=SUBTRACT, opacitymult=0.12)
    g.bind("crazed", "opacitymult", lerp(0.0, 0.25, get("crazing")).graph())

    # ---- creases -----------------------------------------------------------------------------
    g.add("folds", "directionnal_noise", seed=77, scale=2.0)
    g.add("folds_smooth", "blur_hq_grayscale", {"source": "folds"}, intensity=4.0)
    g.add("folds_warp", "warp", {"input1": "folds_smooth", "inputgradient": "broad"}, intensity=0.3)
    g.add("crease_band", "histogram_select", {"input": "folds_warp"}, position=0.5, range=0.008, contrast=0.95)
    g.add("crease_soft", "blur_hq_grayscale", {"source": "crease_band"}, intensity=0.6)
    g.add("crease_lines", "blend", {"source": "crease_area", "destination": "crease_soft"},
          blendingmode=MULTIPLY, opacitymult=1.0)
    g.add("creased", "blend", {"source": "crease_lines", "destination": "crazed"},
          blendingmode=SUBTRACT, opacitymult=0.2)
    g.bind("creased", "opacitymult", lerp(0.0, 0.4, get("creases")).graph())

    # ---- wear and scuffs ---------------------------------------------------------------------
    g.add("wear_spots", "clouds_2", seed=78, scale=5.0)
    g.add("wear_src", "blend", {"source": "wear_spots", "destination": "broad"},
          blendingmode=ADD_SUB, opacitymult=0.2)
    g.add("worn", "histogram_scan", {"input_1": "wear_src"}, position=0.45, contrast=0.15)
    g.bind("worn", "position", lerp(0.85, 0.2, get("wear")).graph())
    g.add("scratches", "scratches_generator", seed=79, amount=8, length=0.8, width=0.012,
          angle_random=1.0, length_random=0.6, luminance_random=0.5)
    g.add("scuffs_soft", "blur", {"input1": "scratches"}, intensity=0.5)
    g.add("scuffs", "levels", {"input1": "scuffs_soft"}, levelouthigh=(0.6, 0.6, 0.6, 1.0))
    g.bind("scuffs", "levelouthigh", vector(lerp(0.1, 1.0, get("wear")), lerp(0.1, 1.0, get("wear")),
                                             lerp(0.1, 1.0, get("wear")), 1.0).graph())
    g.add("scuffed", "blend", {"source": "scuffs", "destination": "creased"},
          blendingmode=SUBTRACT, opacitymult=0.08)

    # ---- height and normal -------------------------------------------------------------------
    g.add("height", "histogram_range", {"input": "scuffed"}, range=1.0, position=0.5)
    normal_and_ao(g, "height", intensity=2.0, height_depth=0.1, spreading=0.05)

    # ---- colour ------------------------------------------------------------------------------
    g.add("dye", "uniform", outputcolor=(0.34, 0.18, 0.09, 1.0))
    g.bind("dye", "outputcolor", vector(get("leather_color", 3), 1.0).graph())
    gradient_over(g, "dye_varied", "variegation", "flow",
                  [(0.0, (0.36, 0.36, 0.36)), (0.5, (0.50, 0.50, 0.50)), (1.0, (0.64, 0.62, 0.58))], "dye",
                  blendingmode=SOFT_LIGHT, opacitymult=0.5)
    color_over(g, "dye_worn", "worn_tone", (0.50, 0.44, 0.38, 1.0), "dye_varied", mask="worn", blendingmode=SCREEN,
               opacitymult=0.6)
    g.add("dye_scuffed", "blend", {"source": "worn_tone", "destination": "dye_worn", "opacity": "scuffs"},
          blendingmode=SCREEN, opacitymult=0.35)
    color_over(g, "dye_crazed", "grime", (0.30, 0.27, 0.25, 1.0), "dye_scuffed", mask="craze_masked",
               blendingmode=MULTIPLY, opacitymult=0.5)
    g.bind("dye_crazed", "opacitymult", lerp(0.0, 0.7, get("crazing")).graph())
    g.add("dye_dark", "blend", {"source": "grime", "destination": "dye_crazed", "opacity": "crease_lines"},
          blendingmode=MULTIPLY, opacitymult=0.6)
    g.bind("dye_dark", "opacitymult", lerp(0.0, 1.0, get("creases")).graph())
    ao_darken(g, "basecolor", "dye_dark", floor=0.35, opacitymult=0.3)

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_base", "histogram_range", {"input": "flow"}, range=0.1, position=0.5)
    g.bind("rough_base", "position", get("roughness").graph())
    g.add("rough_worn", "blend", {"source": "worn", "destination": "rough_base"},
          blendingmode=ADD, opacitymult=0.15)
    g.add("rough_scuffs", "blend", {"source": "scuffs", "destination": "rough_worn"},
          blendingmode=ADD, opacitymult=0.2)
    g.add("roughness", "blend", {"source": "crease_lines", "destination": "rough_scuffs"},
          blendingmode=ADD, opacitymult=0.15)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "leather"

SAMPLE_RANGES = {
    "exposed.leather_color": ((0.04, 0.03, 0.02), (0.85, 0.80, 0.75)),
    "exposed.wear": (0.1, 0.85),
    "exposed.crazing": (0.1, 0.9),
    "exposed.creases": (0.1, 0.9),
    "exposed.roughness": (0.35, 0.75),
    "craze_area.position": (0.3, 0.65),
    "craze_warp.intensity": (0.02, 0.1),
    "folds_warp.intensity": (0.05, 0.2),
    "crease_area.position": (0.35, 0.65),
    "crease_band.range": (0.004, 0.015),
    "crease_band.contrast": (0.9, 0.98),
    "worn.contrast": (0.05, 0.3),
    "wear_src.opacitymult": (0.05, 0.35),
    "dye_varied.opacitymult": (0.2, 0.8),
    "dye_worn.opacitymult": (0.3, 0.9),
    "craze_cells.width": (0.03, 0.07),
    "craze_area.contrast": (0.1, 0.4),
    "normal.intensity": (1.2, 3.5),
    "variegation.colors": ((0.32, 0.32, 0.32, 1.0, 0.46, 0.46, 0.46, 1.0, 0.58, 0.56, 0.52, 1.0),
                           (0.40, 0.40, 0.40, 1.0, 0.54, 0.54, 0.54, 1.0, 0.68, 0.66, 0.62, 1.0)),
}
