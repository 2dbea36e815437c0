"""Material: polished concrete floor, ground to show cut aggregate specks and stones, faint trowel swirls.

Structure
- Matrix: the cement paste, a flat tone (the exposed colour) mottled by broad clouds (the paste
  cures unevenly) and by a fine sandy speckle (BnW Spots 3 at a high scale), so a close look
  never shows a perfectly flat colour.
- Aggregate: grinding cuts through the stones, so they show as flat, irregular sections flush
  with the surface. Two tile samplers (larger stones and fine grit, random position, rotation,
  size and luminance) are warped by a Perlin noise so the outlines are angular and uneven, and
  thresholded into a stone mask; each stone's random luminance picks its colour through a
  gradient of grey, dark basalt, beige and white quartz tones. How many stones show is the
  exposed ``aggregate`` (the samplers' mask randomness).
- Specks: tiny dark and light specks of sand and air voids (white noise and spots thresholds);
  the darkest are pinholes, a hair below the surface and rougher.
- Trowel marks: the power trowel leaves faint swirling arcs; a swirly noise (Moisture Noise)
  is banded by a histogram select and shows as a slight tone and gloss difference (exposed).
- Height: almost flat: a very gentle undulation, stones a hair proud (they polish harder),
  pinholes sunk; normal (OpenGL) from it at a low intensity; ambient occlusion from the height.
- Roughness: moderately glossy around the exposed roughness, stones glossier, trowel bands and
  pinholes rougher. Metallic 0.

Exposed parameters
- ``concrete_color`` (float3): the cement paste colour, grey to warm grey/beige (slightly
  desaturated by an HSL node, as cement never takes a strong hue: a strongly saturated value
  gives a warm beige, a near-grey one a neutral grey); the stones keep their own
  palette, softened towards it.
- ``aggregate``: how much cut aggregate shows (0 a cream-polish finish, 1 a heavy exposure).
- ``aggregate_contrast``: how strongly the stones' colours stand out from the paste.
- ``trowel_marks``: visibility of the trowel swirls in tone and gloss.
- ``roughness``: mean roughness of the polished finish.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD,
    ADD_SUB,
    COPY,
    MAX,
    OUR_OCCLUSION,
    OVERLAY,
    SOFT_LIGHT,
    SUBTRACT,
    color_over,
    constant_map,
    gradient_keys,
    gradient_over,
    keys_near,
    rgba_near,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph

DISC = 2

# colour keys, module-level so SAMPLE_RANGES can keep their sampled variants near neutral (the
# sampler draws each channel independently: a wide range would tint the tones green or blue)
CLOUD_TONES = [(0.0, (0.43, 0.43, 0.43)), (1.0, (0.57, 0.56, 0.54))]
SAND_TONES = [(0.0, (0.40, 0.40, 0.40)), (0.5, (0.5, 0.5, 0.5)), (1.0, (0.60, 0.59, 0.57))]
STONE_COLORS = [(0.0, (0.20, 0.20, 0.21)), (0.25, (0.33, 0.32, 0.31)), (0.45, (0.52, 0.50, 0.47)),
                (0.65, (0.62, 0.55, 0.46)), (0.82, (0.45, 0.42, 0.40)), (1.0, (0.82, 0.80, 0.76))]
STONE_GRAIN = [(0.0, (0.44, 0.44, 0.44)), (1.0, (0.56, 0.56, 0.56))]
TROWEL_TONE = (0.60, 0.60, 0.60)
SPECK_COLOR = (0.22, 0.21, 0.20)
PINHOLE_COLOR = (0.18, 0.17, 0.16)


def build() -> SbsGraph:
    g = SbsGraph("polished_concrete")
    g.expose("concrete_color", (0.62, 0.58, 0.52), min=0.0, max=1.0)
    g.expose("aggregate", 0.55, min=0.0, max=1.0)
    g.expose("aggregate_contrast", 0.6, min=0.0, max=1.0)
    g.expose("trowel_marks", 0.35, min=0.0, max=1.0)
    g.expose("roughness", 0.3, min=0.05, max=0.8)
    aggregate = get("aggregate")

    # ---- aggregate ---------------------------------------------------------------------------
    g.add("stones_l", "tile_sampler", seed=71, x_amount=9, y_amount=9, pattern=DISC, scale=1.1,
          size_xy=(1.0, 0.7), position_random=0.5, rotation_random=0.5, scale_random=0.6,
          luminance_random=0.8, mask_random=0.5)
    g.bind("stones_l", "mask_random", lerp(0.98, 0.35, aggregate).graph())
    g.add("stones_s", "tile_sampler", seed=72, x_amount=26, y_amount=26, pattern=DISC, scale=0.6,
          size_xy=(1.0, 0.7), position_random=0.5, rotation_random=0.5, scale_random=0.7,
          luminance_random=0.8, mask_random=0.4)
    g.bind("stones_s", "mask_random", lerp(0.95, 0.2, aggregate).graph())
    g.add("edge_noise", "perlin_noise", seed=73, scale=12.0)
    g.add("stones", "blend", {"source": "stones_s", "destination": "stones_l"}, blendingmode=MAX)
    g.add("stones_warp", "warp", {"input1": "stones", "inputgradient": "edge_noise"}, intensity=0.35)
    g.add("stone_mask", "histogram_scan", {"input_1": "stones_warp"}, position=0.92, contrast=0.95)
    g.add("stone_mask_soft", "blur", {"input1": "stone_mask"}, intensity=0.3)

    # ---- specks and pinholes -----------------------------------------------------------------
    g.add("sand", "bnw_spots_3", seed=74, scale=20.0)
    g.add("dark_specks", "histogram_scan", {"input_1": "sand"}, position=0.05, contrast=0.75)
    g.add("grain", "white_noise", seed=75)
    g.add("pinholes", "histogram_scan", {"input_1": "grain"}, position=0.025, contrast=0.8)
    g.add("pinholes_soft", "blur", {"input1": "pinholes"}, intensity=0.4)

    # ---- trowel swirls -----------------------------------------------------------------------
    g.add("swirl", "moisture_noise", seed=76, scale=2.0)
    g.add("trowel_bands", "histogram_select", {"input": "swirl"}, position=0.5, range=0.06, contrast=0.2)
    g.add("trowel_soft", "blur_hq_grayscale", {"source": "trowel_bands"}, intensity=3.0)

    # ---- colour ------------------------------------------------------------------------------
    g.add("paste", "uniform", outputcolor=(0.58, 0.56, 0.52, 1.0))
    g.bind("paste", "outputcolor", vector(get("concrete_color", 3), 1.0).graph())
    g.add("paste_muted", "hsl", {"input1": "paste"}, hue=0.5, saturation=0.38, luminosity=0.5)
    g.add("clouds", "clouds_2", seed=77, scale=2.0)
    gradient_over(g, "paste_clouded", "cloud_tones", "clouds", CLOUD_TONES, "paste_muted", blendingmode=SOFT_LIGHT,
                  opacitymult=0.7)
    gradient_over(g, "paste_sandy", "sand_tones", "sand", SAND_TONES, "paste_clouded", blendingmode=OVERLAY,
                  opacitymult=0.5)
    color_over(g, "paste_troweled", "trowel_tone", (*TROWEL_TONE, 1.0), "paste_sandy", mask="trowel_soft",
               blendingmode=SOFT_LIGHT, opacitymult=0.4)
    g.bind("paste_troweled", "opacitymult", lerp(0.0, 0.9, get("trowel_marks")).graph())

    g.add("stone_colors", "gradient", {"input1": "stones_warp"}, **gradient_keys(STONE_COLORS))
    gradient_over(g, "stones_grained", "stone_grain", "grain", STONE_GRAIN, "stone_colors", blendingmode=OVERLAY,
                  opacitymult=0.5)
    g.add("stones_softened", "blend", {"source": "paste_clouded", "destination": "stones_grained"},
          blendingmode=COPY, opacitymult=0.4)
    g.bind("stones_softened", "opacitymult", lerp(0.85, 0.0, get("aggregate_contrast")).graph())
    g.add("with_stones", "blend", {"source": "stones_softened", "destination": "paste_troweled",
                                   "opacity": "stone_mask_soft"}, blendingmode=COPY, opacitymult=1.0)
    color_over(g, "specked", "speck_color", (*SPECK_COLOR, 1.0), "with_stones", mask="dark_specks", blendingmode=COPY,
               opacitymult=0.7)
    color_over(g, "basecolor", "pinhole_color", (*PINHOLE_COLOR, 1.0), "specked", mask="pinholes_soft",
               blendingmode=COPY, opacitymult=0.8)

    # ---- height and normal -------------------------------------------------------------------
    g.add("undulation", "blur_hq_grayscale", {"source": "clouds"}, intensity=6.0)
    g.add("h_base", "histogram_range", {"input": "undulation"}, range=0.15, position=0.5)
    g.add("h_stones", "blend", {"source": "stone_mask_soft", "destination": "h_base"},
          blendingmode=ADD, opacitymult=0.05)
    g.add("h_pinholes", "blend", {"source": "pinholes_soft", "destination": "h_stones"},
          blendingmode=SUBTRACT, opacitymult=0.3)
    g.add("height", "histogram_range", {"input": "h_pinholes"}, range=0.9, position=0.5)
    g.add("normal_main", "normal", {"input1": "height"}, intensity=0.8, inversedy=True)
    g.add("normal_sand", "normal", {"input1": "sand"}, intensity=0.04, inversedy=True)
    g.add("normal", "normal_combine", {"input": "normal_main", "input_1": "normal_sand"})
    g.add("ao", "ambient_occlusion_2", {"source": "height"}, height_depth=0.05, spreading=0.05,
          model=OUR_OCCLUSION)

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_base", "histogram_range", {"input": "clouds"}, range=0.08, position=0.3)
    g.bind("rough_base", "position", get("roughness").graph())
    g.add("rough_stones", "blend", {"source": "stone_mask_soft", "destination": "rough_base"},
          blendingmode=SUBTRACT, opacitymult=0.07)
    g.add("rough_trowel", "blend", {"source": "trowel_soft", "destination": "rough_stones"},
          blendingmode=ADD_SUB, opacitymult=0.1)
    g.bind("rough_trowel", "opacitymult", lerp(0.0, 0.25, get("trowel_marks")).graph())
    g.add("roughness", "blend", {"source": "pinholes_soft", "destination": "rough_trowel"},
          blendingmode=ADD, opacitymult=0.4)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "plaster"

SAMPLE_RANGES = {
    "exposed.concrete_color": ((0.44, 0.42, 0.38), (0.72, 0.68, 0.62)),
    "paste_muted.saturation": (0.34, 0.42),
    "paste_muted.hue": (0.49, 0.51),
    "exposed.aggregate": (0.1, 1.0),
    "exposed.aggregate_contrast": (0.2, 1.0),
    "exposed.trowel_marks": (0.0, 0.8),
    "exposed.roughness": (0.15, 0.55),
    "stones_l.scale_random": (0.3, 0.8),
    "stones_warp.intensity": (0.15, 0.7),
    "stone_mask.position": (0.88, 0.97),
    "paste_clouded.opacitymult": (0.3, 1.0),
    "paste_sandy.opacitymult": (0.2, 0.8),
    "specked.opacitymult": (0.3, 0.9),
    "normal_main.intensity": (0.3, 1.5),
    "normal_sand.intensity": (0.0, 0.1),
    "dark_specks.position": (0.02, 0.08),
    "pinholes.position": (0.005, 0.04),
    "edge_noise.scale": (8.0, 16.0),
    "clouds.scale": (1.5, 4.0),
    "swirl.scale": (1.5, 3.0),
    "cloud_tones.colors": keys_near(CLOUD_TONES, 0.03),
    "sand_tones.colors": keys_near(SAND_TONES, 0.03),
    "stone_colors.colors": keys_near(STONE_COLORS, 0.05),
    "stone_grain.colors": keys_near(STONE_GRAIN, 0.03),
    "trowel_tone.outputcolor": rgba_near(TROWEL_TONE, 0.05),
    "speck_color.outputcolor": rgba_near(SPECK_COLOR, 0.06),
    "pinhole_color.outputcolor": rgba_near(PINHOLE_COLOR, 0.05),
}
