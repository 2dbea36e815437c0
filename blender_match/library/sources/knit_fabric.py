"""Material: stockinette knit (jersey, sweater): columns of V-shaped yarn loops, soft and heathered.

Structure
- Stitches: the face of stockinette is columns of Vs, each V the two legs of one loop. Two Tile
  Generators with one layout (20 columns x 28 courses) draw the legs as elongated paraboloids,
  one tilted each way; each is shifted a quarter column sideways (transformation offset, which
  tiles), so a left leg and a right leg meet at the bottom of every V. Legs are taller than a
  course, so each V tucks under the one above, as the loops interlock. Per-leg luminance and a
  little scale/position randomness keep the loops from looking machined.
- Yarn: the legs are twisted plies: a fine anisotropic noise turned a quarter turn (integer
  matrix, tiles) runs along the columns and is multiplied in, plus fuzz from a fine Gaussian noise.
- Height: the two leg sets combined by maximum, plied, fuzzed; a broad cloud adds the slight
  unevenness of a garment lying on a table. Normal from it (OpenGL) with a fuzz detail normal;
  ambient occlusion darkens the gaps between loops.
- Colour: the exposed yarn colour; heathering (two-tone fibres) mixes in the second fibre colour
  through short horizontal flecks (an anisotropic noise along the courses, thresholded), as a
  two-colour yarn shows; loops shaded by their height and the occlusion.
- Roughness: high (wool/cotton scatters), gaps rougher. Metallic 0.

Exposed parameters
- ``yarn_color`` (float3): the main yarn colour (any dye).
- ``heather_color`` (float3): colour of the second fibre of a heathered yarn.
- ``heather``: how much of the second fibre shows (0 solid colour, 1 strongly marled).
- ``stitch_depth``: how deeply the loops stand out (normal intensity, gap shading).
- ``fuzz``: surface hairiness (fine noise in the height and colour).
- ``roughness``: the yarn's mean roughness.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD_SUB,
    COPY,
    MAX,
    MULTIPLY,
    OUR_OCCLUSION,
    SOFT_LIGHT,
    TILES_MAX,
    ao_darken,
    constant_map,
    gradient_over,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph

COLS, ROWS = 20, 28


def build() -> SbsGraph:
    g = SbsGraph("knit_fabric")
    g.expose("yarn_color", (0.58, 0.53, 0.47), min=0.0, max=1.0)
    g.expose("heather_color", (0.30, 0.27, 0.24), min=0.0, max=1.0)
    g.expose("heather", 0.3, min=0.0, max=1.0)
    g.expose("stitch_depth", 0.55, min=0.0, max=1.0)
    g.expose("fuzz", 0.4, min=0.0, max=1.0)
    g.expose("roughness", 0.88, min=0.5, max=1.0)

    # ---- stitches: left and right legs of every V ---------------------------------------------
    # each leg reaches into the rows above and below; overlapping legs keep the higher (Max
    # blending), so the stitches stay distinct where Add would sum them to white
    legs = dict(x_amount=COLS, y_amount=ROWS, pattern=3, scale=1.0, size_xy=(0.62, 1.75),
                luminance_random=0.25, position_random=0.02, scale_random=0.08)
    g.add("legs_l_src", "tile_generator", blending_mode=TILES_MAX, seed=61, rotation=0.06, **legs)
    g.add("legs_r_src", "tile_generator", blending_mode=TILES_MAX, seed=62, rotation=0.94, **legs)
    quarter = 0.25 / COLS
    g.add("legs_l", "transformation", {"input1": "legs_l_src"}, offset=(quarter, 0.0))
    g.add("legs_r", "transformation", {"input1": "legs_r_src"}, offset=(-quarter, 0.0))
    g.add("loops", "blend", {"source": "legs_r", "destination": "legs_l"}, blendingmode=MAX, opacitymult=1.0)

    # ---- yarn plies and fuzz -----------------------------------------------------------------
    g.add("ply_src", "anisotropic_noise", seed=63, x_amount=48, y_amount=256, smoothness=0.5)
    g.add("ply", "transformation", {"input1": "ply_src"}, matrix22=(0.0, 1.0, -1.0, 0.0))
    g.add("loops_plied", "blend", {"source": "ply", "destination": "loops"},
          blendingmode=MULTIPLY, opacitymult=0.25)
    g.add("fuzz_noise", "gaussian_noise", seed=64, scale=12.0)
    g.add("fuzz_soft", "blur", {"input1": "fuzz_noise"}, intensity=0.4)
    g.add("fuzzed", "blend", {"source": "fuzz_soft", "destination": "loops_plied"},
          blendingmode=ADD_SUB, opacitymult=0.1)
    g.bind("fuzzed", "opacitymult", lerp(0.0, 0.3, get("fuzz")).graph())
    g.add("lie", "clouds_1", seed=65, scale=2.0)
    g.add("uneven", "blend", {"source": "lie", "destination": "fuzzed"},
          blendingmode=ADD_SUB, opacitymult=0.08)
    g.add("height", "histogram_range", {"input": "uneven"}, range=1.0, position=0.5)
    g.add("normal_main", "normal", {"input1": "height"}, intensity=3.0, inversedy=True)
    g.bind("normal_main", "intensity", lerp(1.0, 10.0, get("stitch_depth")).graph())
    g.add("normal_fuzz", "normal", {"input1": "fuzz_soft"}, intensity=0.4, inversedy=True)
    g.add("normal", "normal_combine", {"input": "normal_main", "input_1": "normal_fuzz"})
    g.add("ao", "ambient_occlusion_2", {"source": "height"}, height_depth=0.15, spreading=0.05,
          model=OUR_OCCLUSION)

    # ---- colour ------------------------------------------------------------------------------
    g.add("yarn", "uniform", outputcolor=(0.58, 0.53, 0.47, 1.0))
    g.bind("yarn", "outputcolor", vector(get("yarn_color", 3), 1.0).graph())
    g.add("second", "uniform", outputcolor=(0.30, 0.27, 0.24, 1.0))
    g.bind("second", "outputcolor", vector(get("heather_color", 3), 1.0).graph())
    g.add("fleck_noise", "anisotropic_noise", seed=66, x_amount=64, y_amount=128, smoothness=0.3)
    g.add("fleck_fine", "gaussian_noise", seed=67, scale=6.0)
    g.add("fleck_mix", "blend", {"source": "fleck_fine", "destination": "fleck_noise"},
          blendingmode=SOFT_LIGHT, opacitymult=0.8)
    g.add("fleck_on_legs", "blend", {"source": "loops", "destination": "fleck_mix"},
          blendingmode=MULTIPLY, opacitymult=0.7)
    g.add("flecks", "histogram_scan", {"input_1": "fleck_on_legs"}, position=0.4, contrast=0.4)
    g.bind("flecks", "position", lerp(0.1, 0.9, get("heather")).graph())
    g.add("heathered", "blend", {"source": "second", "destination": "yarn", "opacity": "flecks"},
          blendingmode=COPY, opacitymult=0.9)
    gradient_over(g, "shaded", "shade", "height",
                  [(0.0, (0.12, 0.12, 0.12)), (0.5, (0.72, 0.72, 0.72)), (1.0, (1.0, 1.0, 1.0))], "heathered",
                  blendingmode=MULTIPLY, opacitymult=0.6)
    g.bind("shaded", "opacitymult", lerp(0.4, 1.0, get("stitch_depth")).graph())
    gradient_over(g, "fuzz_colored", "fuzz_tone", "fuzz_soft", [(0.0, (0.42, 0.42, 0.42)), (1.0, (0.60, 0.60, 0.60))],
                  "shaded", blendingmode=SOFT_LIGHT, opacitymult=0.5)
    g.bind("fuzz_colored", "opacitymult", lerp(0.1, 0.9, get("fuzz")).graph())
    ao_darken(g, "basecolor", "fuzz_colored", floor=0.3, opacitymult=0.5)

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_inv", "invert_grayscale", {"source": "height"})
    g.add("roughness", "histogram_range", {"input": "rough_inv"}, range=0.12, position=0.88)
    g.bind("roughness", "position", get("roughness").graph())
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "fabric"

SAMPLE_RANGES = {
    "exposed.yarn_color": ((0.03, 0.03, 0.03), (0.92, 0.90, 0.88)),
    "exposed.heather_color": ((0.03, 0.03, 0.03), (0.92, 0.90, 0.88)),
    "exposed.heather": (0.0, 0.8),
    "exposed.stitch_depth": (0.3, 0.9),
    "exposed.fuzz": (0.1, 0.8),
    "exposed.roughness": (0.75, 0.97),
    "legs_l_src.luminance_random": (0.1, 0.4),
    "legs_r_src.luminance_random": (0.1, 0.4),
    "loops_plied.opacitymult": (0.1, 0.4),
    "uneven.opacitymult": (0.0, 0.15),
    "heathered.opacitymult": (0.6, 1.0),
    # the V geometry: legs keep their tilt, proportions and quarter-column offsets
    "legs_l_src.rotation": (0.04, 0.08),
    "legs_r_src.rotation": (0.92, 0.96),
    "legs_l_src.size_xy": ((0.55, 1.6), (0.7, 1.9)),
    "legs_r_src.size_xy": ((0.55, 1.6), (0.7, 1.9)),
    "legs_l.offset": ((0.25 / COLS, 0.0), (0.25 / COLS, 0.0)),
    "legs_r.offset": ((-0.25 / COLS, 0.0), (-0.25 / COLS, 0.0)),
}
