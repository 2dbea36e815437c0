"""Mossy soil: dark forest soil with cushions of green moss, small twigs, rootlets and a few pebbles.

Structure
- Soil: crumbly dark earth: broad clouds, clods (BnW Spots 1) and a fine crumb grain (BnW Spots 3).
- Moss: patches thresholded from a cloud noise (how much of the soil they cover is the exposed moss
  amount), their edges frayed by a fine noise; inside, a dense fuzzy relief of tiny tufts (a fine
  Perlin noise plus a grain) raised above the soil as soft cushions.
- Twigs and rootlets: two Scratches generators (few thicker twigs, more thin rootlets), bent by a
  noise warp so they are not ruler-straight; they lie on top of soil and moss.
- Pebbles: a sparse Tile Sampler of small rounded stones (most tiles masked out), half sunk in the
  soil.
- Colour: the exposed soil colour varied by the clods; moss colour from dark olive in the hollows to
  a yellow-green on the tuft tips; twigs grey-brown, rootlets reddish brown, pebbles grey; ambient
  occlusion darkens the contacts.
- Height: soil + pebbles (max) + moss cushions + twigs (max); normal from it (OpenGL) with a crumb
  detail normal. Roughness: all rough (moss fuzzy, soil damp around the exposed value), pebbles
  smoother. Metallic 0.

Exposed parameters
- ``soil_color`` (float3, sRGB): the colour of the bare soil.
- ``moss_color`` (float3, sRGB): the mid colour of the moss (fresh green to dry olive).
- ``moss_amount``: how much of the soil the moss covers.
- ``debris``: how many twigs, rootlets and pebbles lie about.
- ``roughness``: roughness of the soil (lower when wet).
- ``relief``: the strength of the normal map.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD_SUB,
    COPY,
    MAX,
    MULTIPLY,
    OUR_OCCLUSION,
    constant_map,
    gradient_over,
    keys_near,
    set_material_outputs,
)
from blender_match.library.expressions import const, get, lerp, vector
from blender_match.translator.runtime import SbsGraph

SOIL_TONES = [(0.0, (0.55, 0.55, 0.55)), (0.5, (0.85, 0.85, 0.85)), (1.0, (1.0, 1.0, 1.0))]
MOSS_TONES = [(0.0, (0.25, 0.25, 0.2)), (0.35, (0.6, 0.62, 0.55)), (0.7, (1.0, 1.0, 0.95)),
              (1.0, (1.0, 1.0, 0.6))]
EDGE_TONES = [(0.0, (0.45, 0.42, 0.40)), (0.6, (0.9, 0.9, 0.9)), (1.0, (1.0, 1.0, 1.0))]
TWIG_TONES = [(0.0, (0.16, 0.12, 0.09)), (0.5, (0.30, 0.24, 0.18)), (1.0, (0.46, 0.40, 0.33))]
ROOT_TONES = [(0.0, (0.20, 0.11, 0.07)), (1.0, (0.42, 0.26, 0.16))]
PEBBLE_TONES = [(0.0, (0.12, 0.11, 0.10)), (0.5, (0.22, 0.21, 0.19)), (1.0, (0.34, 0.32, 0.29))]
AO_TONES = [(0.0, (0.2, 0.2, 0.2)), (1.0, (1.0, 1.0, 1.0))]


def build() -> SbsGraph:
    g = SbsGraph("mossy_soil")
    g.expose("soil_color", (0.17, 0.12, 0.08), min=0.0, max=1.0)
    g.expose("moss_color", (0.24, 0.33, 0.09), min=0.0, max=1.0)
    g.expose("moss_amount", 0.5, min=0.0, max=1.0)
    g.expose("debris", 0.5, min=0.0, max=1.0)
    g.expose("roughness", 0.88, min=0.4, max=1.0)
    g.expose("relief", 0.6, min=0.0, max=1.0)
    moss = get("moss_amount")
    debris = get("debris")

    # ---- soil ----------------------------------------------------------------------------------
    g.add("broad", "clouds_2", seed=81, scale=3.0)
    g.add("clods", "bnw_spots_1", seed=82, scale=8.0)
    g.add("crumbs", "bnw_spots_3", seed=83, scale=24.0)
    g.add("soil_a", "blend", {"source": "clods", "destination": "broad"}, blendingmode=ADD_SUB, opacitymult=0.35)
    g.add("soil_b", "blend", {"source": "crumbs", "destination": "soil_a"}, blendingmode=ADD_SUB,
          opacitymult=0.25)
    g.add("soil_h", "histogram_range", {"input": "soil_b"}, range=0.3, position=0.25)

    # ---- pebbles -------------------------------------------------------------------------------
    g.add("pebbles", "tile_sampler", seed=84, x_amount=10, y_amount=10, pattern=3, scale=0.9,
          size_xy=(1.0, 0.75), position_random=0.5, rotation_random=0.5, scale_random=0.6,
          luminance_random=0.5, mask_random=0.8)
    g.bind("pebbles", "mask_random", lerp(0.98, 0.6, debris).graph())
    for param in ("offset", "rotation"):  # meaningless with random positions and rotations
        g.bind("pebbles", param, const(0.0).graph())
    g.add("pebbles_h", "histogram_range", {"input": "pebbles"}, range=0.5, position=0.4)
    g.add("pebble_mask", "histogram_scan", {"input_1": "pebbles"}, position=0.95, contrast=0.9)

    # ---- moss ----------------------------------------------------------------------------------
    g.add("patches", "clouds_1", seed=85, scale=3.0)
    g.add("fray", "bnw_spots_3", seed=86, scale=12.0)
    g.add("patches_frayed", "blend", {"source": "fray", "destination": "patches"}, blendingmode=ADD_SUB,
          opacitymult=0.12)
    g.add("moss_mask", "histogram_scan", {"input_1": "patches_frayed"}, position=0.5, contrast=0.75)
    g.bind("moss_mask", "position", lerp(0.05, 0.95, moss).graph())
    g.add("moss_cushion", "blur_hq_grayscale", {"source": "moss_mask"}, intensity=2.0)
    g.add("tufts", "bnw_spots_3", seed=87, scale=32.0)
    g.add("tuft_grain", "gaussian_noise", seed=88, scale=4.0)
    g.add("tufts_b", "blend", {"source": "tuft_grain", "destination": "tufts"}, blendingmode=ADD_SUB,
          opacitymult=0.5)
    g.add("moss_top", "blend", {"source": "tufts_b", "destination": "moss_cushion"}, blendingmode=MULTIPLY,
          opacitymult=0.45)
    g.add("moss_h", "histogram_range", {"input": "moss_top"}, range=0.45, position=0.42)
    g.add("h_moss", "blend", {"source": "moss_h", "destination": "soil_h", "opacity": "moss_mask"},
          blendingmode=MAX)
    g.add("h_soil", "blend", {"source": "pebbles_h", "destination": "h_moss", "opacity": "pebble_mask"},
          blendingmode=MAX)

    # ---- twigs and rootlets ------------------------------------------------------------------
    g.add("bend", "perlin_noise", seed=89, scale=6.0)
    g.add("twigs_raw", "scratches_generator", seed=90, amount=3, length=0.9, width=0.022, angle_random=1.0,
          length_random=0.6, luminance_random=0.3, mask_random=0.3)
    g.bind("twigs_raw", "mask_random", lerp(1.0, 0.0, debris).graph())
    g.add("twigs", "warp", {"input1": "twigs_raw", "inputgradient": "bend"}, intensity=0.4)
    g.add("roots_raw", "scratches_generator", seed=91, amount=7, length=1.1, width=0.012, angle_random=1.0,
          length_random=0.7, luminance_random=0.4, mask_random=0.4)
    g.bind("roots_raw", "mask_random", lerp(1.0, 0.2, debris).graph())
    for node in ("twigs_raw", "roots_raw"):  # any direction: the base angle means nothing
        g.bind(node, "angle", const(0.0).graph())
    g.add("roots", "warp", {"input1": "roots_raw", "inputgradient": "bend"}, intensity=0.8)
    g.add("twig_mask", "histogram_scan", {"input_1": "twigs"}, position=0.9, contrast=0.7)
    g.add("root_mask", "histogram_scan", {"input_1": "roots"}, position=0.9, contrast=0.7)
    g.add("twigs_h", "histogram_range", {"input": "twigs"}, range=0.35, position=0.75)
    g.add("h_roots", "blend", {"source": "roots", "destination": "h_soil", "opacity": "root_mask"},
          blendingmode=MAX, opacitymult=0.55)
    g.add("height", "blend", {"source": "twigs_h", "destination": "h_roots", "opacity": "twig_mask"},
          blendingmode=MAX)

    # ---- normal and occlusion -----------------------------------------------------------------
    g.add("n_main", "normal", {"input1": "height"}, intensity=6.0, inversedy=True, input2alpha=False)
    g.bind("n_main", "intensity", lerp(1.0, 12.0, get("relief")).graph())
    g.add("n_crumbs", "normal", {"input1": "crumbs"}, intensity=0.8, inversedy=True, input2alpha=False)
    g.add("normal", "normal_combine", {"input": "n_main", "input_1": "n_crumbs"})
    g.add("ao", "ambient_occlusion_2", {"source": "height"}, height_depth=0.2, spreading=0.08,
          model=OUR_OCCLUSION)

    # ---- colour --------------------------------------------------------------------------------
    g.add("soil_base", "uniform", outputcolor=(0.17, 0.12, 0.08, 1.0))
    g.bind("soil_base", "outputcolor", vector(get("soil_color", 3), 1.0).graph())
    gradient_over(g, "soil_col", "soil_tones", "soil_b", SOIL_TONES, "soil_base", blendingmode=MULTIPLY)
    g.add("moss_base", "uniform", outputcolor=(0.24, 0.33, 0.09, 1.0))
    g.bind("moss_base", "outputcolor", vector(get("moss_color", 3), 1.0).graph())
    gradient_over(g, "moss_tinted", "moss_tones", "tufts_b", MOSS_TONES, "moss_base", blendingmode=MULTIPLY)
    gradient_over(g, "moss_col", "edge_tones", "moss_cushion", EDGE_TONES, "moss_tinted", blendingmode=MULTIPLY)
    g.add("with_moss", "blend", {"source": "moss_col", "destination": "soil_col", "opacity": "moss_mask"},
          blendingmode=COPY)
    gradient_over(g, "with_pebbles", "pebble_tones", "pebbles", PEBBLE_TONES, "with_moss", mask="pebble_mask",
                  blendingmode=COPY)
    gradient_over(g, "with_roots", "root_tones", "roots", ROOT_TONES, "with_pebbles", mask="root_mask",
                  blendingmode=COPY)
    gradient_over(g, "with_twigs", "twig_tones", "twigs", TWIG_TONES, "with_roots", mask="twig_mask", blendingmode=COPY)
    gradient_over(g, "basecolor", "ao_color", "ao", AO_TONES, "with_twigs", blendingmode=MULTIPLY, opacitymult=0.5)

    # ---- roughness and metallic ---------------------------------------------------------------
    g.add("rough_soil", "histogram_range", {"input": "crumbs"}, range=0.1, position=0.88)
    g.bind("rough_soil", "position", get("roughness").graph())
    g.add("rough_moss", "uniform", colorswitch=False, outputcolor=(0.96, 0.96, 0.96, 1.0))
    g.add("rough_m", "blend", {"source": "rough_moss", "destination": "rough_soil", "opacity": "moss_mask"},
          blendingmode=COPY)
    g.add("rough_peb", "uniform", colorswitch=False, outputcolor=(0.8, 0.8, 0.8, 1.0))
    g.add("roughness", "blend", {"source": "rough_peb", "destination": "rough_m", "opacity": "pebble_mask"},
          blendingmode=COPY)
    constant_map(g, "metallic", 0.0)

    set_material_outputs(g, ambient_occlusion="ao")
    return g


FAMILY = "ground"

SAMPLE_RANGES = {
    "exposed.soil_color": ((0.12, 0.08, 0.05), (0.24, 0.17, 0.12)),
    "exposed.moss_color": ((0.17, 0.27, 0.06), (0.32, 0.40, 0.14)),
    "exposed.moss_amount": (0.2, 0.85),
    "exposed.debris": (0.1, 0.9),
    "exposed.roughness": (0.7, 0.97),
    "exposed.relief": (0.3, 1.0),
    "broad.scale": (2.0, 5.0),
    "clods.scale": (5.0, 12.0),
    "crumbs.scale": (18.0, 30.0),
    "patches.scale": (2.0, 4.0),
    "fray.scale": (8.0, 16.0),
    "tufts.scale": (24.0, 32.0),
    "bend.scale": (4.0, 8.0),
    "twigs.intensity": (0.1, 0.8),
    "roots.intensity": (0.3, 1.2),
    "moss_cushion.intensity": (1.0, 4.0),
    "soil_tones.colors": keys_near(SOIL_TONES, 0.03),
    "moss_tones.colors": keys_near(MOSS_TONES, 0.03),
    "edge_tones.colors": keys_near(EDGE_TONES, 0.03),
    "twig_tones.colors": keys_near(TWIG_TONES, 0.03),
    "root_tones.colors": keys_near(ROOT_TONES, 0.03),
    "pebble_tones.colors": keys_near(PEBBLE_TONES, 0.03),
    "ao_color.colors": keys_near(AO_TONES, 0.05),
    "n_crumbs.intensity": (0.3, 1.5),
}
