"""Material: perforated steel or aluminium sheet, bare, brushed or painted, with staggered round holes.

Structure
- Holes: a Tile Generator of discs, 20 across and 24 down with alternate rows shifted half a
  cell: the 60-degree staggered pattern of punched sheet (24/20 is close to 2/sqrt(3), and the
  discs are stretched 1.2 in y so they stay round in the shorter cells). About 1.5 cm pitch on a
  30 cm sample. A slight softness and a small blur round the punched edge.
- Height: the plate at the top, the holes deep at 0 (through the sheet a dark backdrop shows),
  a faint brushing relief on the plate; normal from it.
- Brushing: horizontal anisotropic streaks and fine smeared noise, used in colour, roughness and
  relief (exposed strength, 0 for a plain rolled or painted sheet).
- Finish: the exposed colour on the plate; ``paint`` moves it from bare metal (metallic 1,
  glossier) to a paint film (metallic 0, a little rougher). Paint chips off around the hole
  edges (a ring from the blurred holes, broken up by a grunge map; exposed wear) showing bare
  grey steel.
- Holes: near-black, fully rough, non-metallic backdrop in colour, roughness and metallic.
- Anisotropy: the brushing stretches the plate's highlight across the streaks, which run along
  +u (angle 0): the level is ``brushing`` on bare metal, nothing under paint.

Exposed parameters
- ``finish_color`` (float3): the plate colour: steel/aluminium grey or any paint colour.
- ``hole_size``: hole diameter relative to the pitch (open area).
- ``roughness``: mean roughness of the plate.
- ``paint``: 0 bare metal to 1 painted (metallic and gloss of the plate).
- ``brushing``: strength of the brushed streaks.
- ``wear``: paint chipped off around the hole edges.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD_SUB,
    MULTIPLY,
    OVERLAY,
    SUBTRACT,
    TILES_MAX,
    brushing,
    color_over,
    gradient_over,
    normal_and_ao,
    set_material_outputs,
)
from blender_match.library.expressions import get, gray4, lerp, vector
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("perforated_metal")
    g.expose("finish_color", (0.62, 0.63, 0.65), min=0.0, max=1.0)
    g.expose("hole_size", 0.6, min=0.0, max=1.0)
    g.expose("roughness", 0.35, min=0.05, max=0.9)
    g.expose("paint", 0.0, min=0.0, max=1.0)
    g.expose("brushing", 0.4, min=0.0, max=1.0)
    g.expose("wear", 0.3, min=0.0, max=1.0)

    # ---- holes -------------------------------------------------------------------------------------
    g.add("holes_sharp", "tile_generator", blending_mode=TILES_MAX, x_amount=20, y_amount=24, pattern=2, offset=0.5,
          scale=0.6, size_xy=(1.0, 1.2), softness=0.08)
    g.bind("holes_sharp", "scale", lerp(0.35, 0.75, get("hole_size")).graph())
    g.add("holes", "blur_hq_grayscale", {"source": "holes_sharp"}, intensity=0.4)
    g.add("plate", "invert_grayscale", {"source": "holes"})
    g.add("plate_mask", "histogram_scan", {"input_1": "plate"}, position=0.5, contrast=0.9)

    # ---- brushing ------------------------------------------------------------------------------------
    g.add("streaks", "anisotropic_noise", seed=91, x_amount=3, y_amount=200, smoothness=0.3)
    g.add("speck", "white_noise", seed=92)
    g.add("speck_smear", "dirmotionblur", {"input1": "speck"}, intensity=16.0, mblurangle=0.0)
    g.add("speck_level", "auto_levels", {"input": "speck_smear"})
    g.add("brush_mix", "blend", {"source": "speck_level", "destination": "streaks"},
          blendingmode=OVERLAY, opacitymult=0.5)
    g.add("brush", "histogram_range", {"input": "brush_mix"}, range=0.4, position=0.5)
    g.bind("brush", "range", lerp(0.0, 1.0, get("brushing")).graph())

    # ---- paint wear around the holes -------------------------------------------------------------------
    g.add("holes_wide", "blur_hq_grayscale", {"source": "holes_sharp"}, intensity=3.0)
    g.add("rim", "blend", {"source": "holes_sharp", "destination": "holes_wide"},
          blendingmode=SUBTRACT)
    g.add("rim_level", "auto_levels", {"input": "rim"})
    g.add("chip_grunge", "grunge_map_001", seed=93, scale=4.0)
    g.add("chip_raw", "blend", {"source": "chip_grunge", "destination": "rim_level"},
          blendingmode=MULTIPLY)
    g.add("chips", "histogram_scan", {"input_1": "chip_raw"}, position=0.3, contrast=0.7)
    g.bind("chips", "position", lerp(0.0, 0.6, get("wear") * get("paint")).graph())

    # ---- height and normal -------------------------------------------------------------------------------
    g.add("plate_relief", "blend", {"source": "brush", "destination": "plate"},
          blendingmode=ADD_SUB, opacitymult=0.04)
    g.add("height", "blend", {"source": "chips", "destination": "plate_relief"},
          blendingmode=SUBTRACT, opacitymult=0.03)
    normal_and_ao(g, "height", intensity=2.0, height_depth=0.3, spreading=0.08)

    # ---- colour -----------------------------------------------------------------------------------------------
    g.add("finish", "uniform", outputcolor=(0.62, 0.63, 0.65, 1.0))
    g.bind("finish", "outputcolor", vector(get("finish_color", 3), 1.0).graph())
    gradient_over(g, "finish_brushed", "brush_tone", "brush", [(0.0, (0.40, 0.40, 0.40)), (1.0, (0.60, 0.60, 0.60))],
                  "finish", blendingmode=OVERLAY, opacitymult=0.6)
    color_over(g, "finish_chipped", "bare_steel", (0.58, 0.58, 0.59, 1.0), "finish_brushed", mask="chips")
    g.add("backdrop", "uniform", outputcolor=(0.02, 0.02, 0.02, 1.0))
    g.add("basecolor", "blend", {"source": "finish_chipped", "destination": "backdrop",
                                 "opacity": "plate_mask"})

    # ---- roughness and metallic ------------------------------------------------------------------------------
    g.add("rough_plate", "histogram_range", {"input": "brush"}, range=0.12, position=0.35)
    g.bind("rough_plate", "position", (get("roughness") + 0.15 * get("paint")).graph())
    g.add("rough_chips", "uniform", colorswitch=False, outputcolor=(0.35, 0.35, 0.35, 1.0))
    g.add("rough_chipped", "blend", {"source": "rough_chips", "destination": "rough_plate",
                                     "opacity": "chips"})
    g.add("rough_hole", "uniform", colorswitch=False, outputcolor=(1.0, 1.0, 1.0, 1.0))
    g.add("roughness", "blend", {"source": "rough_chipped", "destination": "rough_hole",
                                 "opacity": "plate_mask"})
    g.add("metal_plate", "uniform", colorswitch=False, outputcolor=(1.0, 1.0, 1.0, 1.0))
    g.bind("metal_plate", "outputcolor", gray4(1.0 - get("paint")).graph())
    g.add("metal_chipped", "blend", {"source": "chips", "destination": "metal_plate"},
          blendingmode=5)
    g.add("metallic", "blend", {"source": "plate_mask", "destination": "metal_chipped"},
          blendingmode=MULTIPLY)

    brushing(g, get("brushing") * (1.0 - get("paint")), 0.0)  # anisotropic noise, motion blur at 0: along +u

    set_material_outputs(g, ambient_occlusion="ao", anisotropy=True)
    return g


FAMILY = "metal"

SAMPLE_RANGES = {
    "exposed.finish_color": ((0.05, 0.05, 0.05), (0.90, 0.90, 0.90)),
    "exposed.hole_size": (0.15, 0.85),
    "exposed.roughness": (0.15, 0.7),
    "exposed.paint": (0.0, 1.0),
    "exposed.brushing": (0.0, 0.9),
    "exposed.wear": (0.0, 0.8),
    "holes_sharp.softness": (0.02, 0.2),
    # a punched sheet is exact: no random holes, shifts, sizes or tilts
    "holes_sharp.offset": (0.5, 0.5),
    "holes_sharp.size_xy": ([0.98, 1.18], [1.02, 1.22]),
    "holes_sharp.interstice": ([0.0, 0.0], [0.0, 0.0]),
    "holes_sharp.position_random": (0.0, 0.0),
    "holes_sharp.scale_random": (0.0, 0.02),
    "holes_sharp.rotation": (0.0, 0.0),
    "holes_sharp.rotation_random": (0.0, 0.0),
    "holes_sharp.luminance_random": (0.0, 0.0),
    "holes_sharp.mask_random": (0.0, 0.0),
    "holes.intensity": (0.2, 0.8),
    "streaks.smoothness": (0.1, 0.6),
    "speck_smear.intensity": (8.0, 28.0),
    "normal.intensity": (1.0, 4.0),
    "chip_grunge.scale": (2.0, 8.0),
    "backdrop.outputcolor": ([0.0, 0.0, 0.0, 1.0], [0.06, 0.06, 0.06, 1.0]),
    "brush_tone.colors": ([0.37, 0.37, 0.37, 1.0, 0.57, 0.57, 0.57, 1.0],
                          [0.43, 0.43, 0.43, 1.0, 0.63, 0.63, 0.63, 1.0]),
    "bare_steel.outputcolor": ([0.55, 0.55, 0.56, 1.0], [0.62, 0.62, 0.63, 1.0]),
}
