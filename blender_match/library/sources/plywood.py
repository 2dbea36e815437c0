"""Material: rotary-cut plywood face veneer (birch/pine): wide wavy grain figure, small knots and patches, pale.

Structure
- Figure: a rotary-peeled veneer cuts the growth rings at a grazing angle, so the rings show as
  wide, wavy, irregular bands and long ovals. Here a smooth noise stretched along the grain
  (Directionnal Noise, turned to run across the sheet) stands for the ring surface; three folds
  (|2x - 1| from two histogram scans and a max blend each) cut it into 8 contour bands, and a
  gradient map draws each band as a pale earlywood zone ending in a darker latewood edge: the
  contour lines of a smooth field are exactly the flowing "cathedral" figure of the peel.
- Fibres: fine streaks along the grain (Wood Fibers 1, turned a quarter to run across) in the
  colour and a little in the height; a fibrous anisotropic noise for the normal detail.
- Knots: a sparse Tile Sampler of small discs (how many: exposed) thresholded into dark pin knots
  with a warm halo, and a few larger ovals drawn as lighter, sharp-edged repair patches (the
  "football" patches of plywood faces).
- Colour: earlywood (the exposed colour) and a darker, warmer latewood through the bands
  (exposed contrast), fibres, clouds, knots and patches.
- Height: almost flat (sanded face): latewood bands a hair proud, fibres, knots; normal (OpenGL)
  combined with the fibre detail. Roughness: matte, around the exposed roughness, knots a little
  smoother. Metallic 0.

Exposed parameters
- ``wood_color`` (float3): earlywood colour (birch nearly white-cream, pine yellow, or a stain).
- ``grain_contrast``: how strongly the latewood bands show.
- ``waviness``: how much the figure meanders (warp of the ring surface by a noise).
- ``knots``: how many pin knots and patches appear.
- ``roughness``: mean roughness.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD,
    ADD_SUB,
    COPY,
    MULTIPLY,
    SOFT_LIGHT,
    SUBTRACT,
    color_over,
    constant_map,
    fold,
    gradient_keys,
    gradient_over,
    keys_near,
    rgba_near,
    set_material_outputs,
)
from blender_match.library.expressions import const, get, lerp, vector
from blender_match.translator.runtime import SbsGraph

FOLDS = 3
DISC = 2
# band profile over the folded field: 0 the latewood edge, 1 the middle of the earlywood
BAND_PROFILE = [(0.0, (0.0, 0.0, 0.0)), (0.06, (0.45, 0.45, 0.45)), (0.25, (0.88, 0.88, 0.88)),
                (1.0, (1.0, 1.0, 1.0))]
FIBRE_TONES = [(0.0, (0.45, 0.45, 0.45)), (1.0, (0.55, 0.55, 0.54))]
CLOUD_TONES = [(0.0, (0.45, 0.45, 0.45)), (1.0, (0.56, 0.55, 0.53))]
KNOT_COLOR = (0.30, 0.18, 0.09)
HALO_COLOR = (0.62, 0.45, 0.30)
PATCH_TONE = (0.60, 0.59, 0.57)


def build() -> SbsGraph:
    g = SbsGraph("plywood")
    g.expose("wood_color", (0.84, 0.70, 0.52), min=0.0, max=1.0)
    g.expose("grain_contrast", 0.55, min=0.0, max=1.0)
    g.expose("waviness", 0.4, min=0.0, max=1.0)
    g.expose("knots", 0.4, min=0.0, max=1.0)
    g.expose("roughness", 0.65, min=0.2, max=1.0)
    turn = (0.0, 1.0, -1.0, 0.0)  # a quarter turn: the grain runs across the sheet

    # ---- figure ------------------------------------------------------------------------------
    g.add("ring_src", "perlin_noise", seed=91, scale=2.0)
    g.add("ring_surface", "transformation", {"input1": "ring_src"}, matrix22=(1.0, 0.0, 0.0, 3.0))
    g.add("meander", "perlin_noise_1", seed=92, scale=3.0)
    g.add("ring_wavy", "warp", {"input1": "ring_surface", "inputgradient": "meander"}, intensity=2.0)
    g.bind("ring_wavy", "intensity", lerp(0.0, 5.0, get("waviness")).graph())
    folded = "ring_wavy"
    for i in range(FOLDS):
        folded = fold(g, folded, i)
    g.add("bands", "gradient", {"input1": folded}, colorswitch=False, **gradient_keys(BAND_PROFILE))
    g.add("late_mask", "invert_grayscale", {"source": "bands"})

    # ---- fibres ------------------------------------------------------------------------------
    g.add("fibres_src", "wood_fibers_1", seed=93, scale=6.0)
    g.add("fibres", "transformation", {"input1": "fibres_src"}, matrix22=turn)
    g.add("raised", "anisotropic_noise", seed=94, x_amount=16, y_amount=256, smoothness=0.3)

    # ---- knots and patches -------------------------------------------------------------------
    g.add("knot_spots", "tile_sampler", seed=95, x_amount=5, y_amount=5, pattern=DISC, scale=0.25,
          size_xy=(1.0, 0.7), position_random=0.5, scale_random=0.5, mask_random=0.7)
    g.bind("knot_spots", "mask_random", lerp(1.0, 0.5, get("knots")).graph())
    g.add("knot_core", "histogram_scan", {"input_1": "knot_spots"}, position=0.8, contrast=0.8)
    g.add("knot_halo", "blur_hq_grayscale", {"source": "knot_core"}, intensity=6.0)
    g.add("patch_spots", "tile_sampler", seed=96, x_amount=3, y_amount=3, pattern=DISC, scale=0.6,
          size_xy=(1.0, 0.45), position_random=0.5, scale_random=0.3, mask_random=0.8)
    g.bind("patch_spots", "mask_random", lerp(1.0, 0.7, get("knots")).graph())
    g.add("patches", "histogram_scan", {"input_1": "patch_spots"}, position=0.9, contrast=0.9)

    # ---- colour ------------------------------------------------------------------------------
    wood = get("wood_color", 3)
    g.add("earlywood", "uniform", outputcolor=(0.84, 0.70, 0.52, 1.0))
    g.bind("earlywood", "outputcolor", vector(wood, 1.0).graph())
    g.add("latewood", "uniform", outputcolor=(0.66, 0.46, 0.28, 1.0))
    g.bind("latewood", "outputcolor", vector(wood * const((0.78, 0.66, 0.54)), 1.0).graph())
    g.add("banded", "blend", {"source": "latewood", "destination": "earlywood", "opacity": "late_mask"},
          blendingmode=COPY, opacitymult=0.55)
    g.bind("banded", "opacitymult", lerp(0.05, 1.0, get("grain_contrast")).graph())
    gradient_over(g, "fibred", "fibre_tones", "fibres", FIBRE_TONES, "banded", blendingmode=SOFT_LIGHT, opacitymult=0.7)
    g.add("clouds", "clouds_2", seed=97, scale=3.0)
    gradient_over(g, "clouded", "cloud_tones", "clouds", CLOUD_TONES, "fibred", blendingmode=SOFT_LIGHT,
                  opacitymult=0.5)
    color_over(g, "patched", "patch_tone", (*PATCH_TONE, 1.0), "clouded", mask="patches", blendingmode=SOFT_LIGHT,
               opacitymult=0.7)
    color_over(g, "haloed", "halo_color", (*HALO_COLOR, 1.0), "patched", mask="knot_halo", blendingmode=MULTIPLY,
               opacitymult=0.6)
    color_over(g, "basecolor", "knot_color", (*KNOT_COLOR, 1.0), "haloed", mask="knot_core", blendingmode=COPY,
               opacitymult=0.9)

    # ---- height and normal -------------------------------------------------------------------
    g.add("h_bands", "histogram_range", {"input": "late_mask"}, range=0.1, position=0.5)
    g.add("h_fibres", "blend", {"source": "fibres", "destination": "h_bands"},
          blendingmode=ADD_SUB, opacitymult=0.08)
    g.add("h_knots", "blend", {"source": "knot_core", "destination": "h_fibres"},
          blendingmode=ADD, opacitymult=0.06)
    g.add("height", "histogram_range", {"input": "h_knots"}, range=1.0, position=0.5)
    g.add("normal_main", "normal", {"input1": "height"}, intensity=2.0, inversedy=True)
    g.add("normal_raised", "normal", {"input1": "raised"}, intensity=0.3, inversedy=True)
    g.add("normal", "normal_combine", {"input": "normal_main", "input_1": "normal_raised"})

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_base", "histogram_range", {"input": "fibres"}, range=0.1, position=0.65)
    g.bind("rough_base", "position", get("roughness").graph())
    g.add("roughness", "blend", {"source": "knot_core", "destination": "rough_base"},
          blendingmode=SUBTRACT, opacitymult=0.12)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g)
    return g


FAMILY = "wood"

SAMPLE_RANGES = {
    "exposed.wood_color": ((0.72, 0.54, 0.34), (0.92, 0.76, 0.58)),
    "exposed.grain_contrast": (0.25, 0.9),
    "exposed.waviness": (0.0, 1.0),
    "exposed.knots": (0.0, 1.0),
    "exposed.roughness": (0.45, 0.85),
    "ring_src.scale": (1.5, 3.0),
    "meander.scale": (2.0, 5.0),
    "fibred.opacitymult": (0.3, 1.0),
    "clouded.opacitymult": (0.2, 0.8),
    "normal_main.intensity": (1.0, 4.0),
    "normal_raised.intensity": (0.1, 0.6),
    "knot_halo.intensity": (3.0, 9.0),
    "bands.positions": ([0.0, 0.03, 0.15, 1.0], [0.0, 0.1, 0.35, 1.0]),
    "fibre_tones.colors": keys_near(FIBRE_TONES, 0.03),
    "cloud_tones.colors": keys_near(CLOUD_TONES, 0.03),
    "knot_color.outputcolor": rgba_near(KNOT_COLOR, 0.05),
    "halo_color.outputcolor": rgba_near(HALO_COLOR, 0.04),
    "patch_tone.outputcolor": rgba_near(PATCH_TONE, 0.03),
    # the folds are exact arithmetic (|2x - 1|): their scans and max blends stay pinned
    **{f"fold{i}_{side}.{param}": (value, value) for i in range(FOLDS) for side in ("hi", "lo")
       for param, value in (("position", 0.25), ("contrast", 0.0))},
    **{f"fold{i}.opacitymult": (1.0, 1.0) for i in range(FOLDS)},
}
