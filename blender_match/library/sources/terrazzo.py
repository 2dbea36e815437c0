"""Polished terrazzo: marble and glass chips of several sizes set in a cement matrix, ground flat.

Structure: two tile samplers (large and small chips, random position, rotation and size, random
luminance per chip) are warped by a Perlin noise so chips get irregular, angular outlines; their
luminance picks each chip's colour through a gradient map (white and grey marble, black, terracotta,
green glass); the matrix gets a fine speckle. Base colour = chips over the matrix; roughness = a
polished level, slightly rougher in the matrix and in small pores; metallic = 0; height = chips
a hair above the matrix, pores below; normal from height.

Exposed parameters: ``matrix_color`` (sRGB), ``chip_density`` (how many chips show),
``chip_contrast`` (colour strength of the chips), ``roughness``, ``pores`` (amount of pores),
``normal_intensity``.
"""
from blender_match.library.authoring import color_over, constant_map, set_material_outputs
from blender_match.library.expressions import get, vector
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("terrazzo")
    g.expose("matrix_color", [0.80, 0.78, 0.74], min=0.0, max=1.0)
    g.expose("chip_density", 0.6, min=0.0, max=1.0)
    g.expose("chip_contrast", 0.8, min=0.0, max=1.0)
    g.expose("roughness", 0.22, min=0.05, max=0.7)
    g.expose("pores", 0.4, min=0.0, max=1.0)
    g.expose("normal_intensity", 0.8, min=0.0, max=4.0)

    # chips
    g.add("chips_large", "tile_sampler", seed=12, x_amount=7, y_amount=7, pattern=1, scale=0.8,
          position_random=0.5, rotation_random=0.5, scale_random=0.5, luminance_random=0.9)
    g.add("chips_small", "tile_sampler", seed=27, x_amount=18, y_amount=18, pattern=1, scale=0.6,
          position_random=0.5, rotation_random=0.5, scale_random=0.6, luminance_random=0.9)
    g.bind("chips_large", "mask_random", (0.9 - 0.9 * get("chip_density")).graph())
    g.bind("chips_small", "mask_random", (0.8 - 0.8 * get("chip_density")).graph())
    g.add("warp_noise", "perlin_noise", seed=5, scale=6.0)
    g.add("chips_large_warp", "warp", {"input1": "chips_large", "inputgradient": "warp_noise"}, intensity=1.2)
    g.add("chips_small_warp", "warp", {"input1": "chips_small", "inputgradient": "warp_noise"}, intensity=0.8)
    g.add("chips_all", "blend", {"source": "chips_small_warp", "destination": "chips_large_warp"}, blendingmode=5)
    g.add("chip_mask_raw", "histogram_scan", {"input_1": "chips_all"}, position=0.96, contrast=0.97)
    g.add("chip_mask", "blur", {"input1": "chip_mask_raw"}, intensity=0.3)

    # chip colours: the chip luminance picks a colour
    g.add("chip_colors", "gradient", {"input1": "chips_all"}, interpmode=0,
          positions=[0.0, 0.3, 0.45, 0.6, 0.72, 0.85, 1.0],
          colors=[0.93, 0.92, 0.9, 1.0, 0.62, 0.61, 0.6, 1.0, 0.09, 0.09, 0.1, 1.0, 0.55, 0.25, 0.15, 1.0,
                  0.28, 0.42, 0.33, 1.0, 0.85, 0.83, 0.8, 1.0, 0.38, 0.37, 0.37, 1.0])
    g.add("chip_grain", "gaussian_noise", seed=3, scale=16.0)
    color_over(g, "chip_colors_grain", "chip_grain_tone", [0.85, 0.85, 0.85, 1.0], "chip_colors", mask="chip_grain",
               blendingmode=3, opacitymult=0.4)

    # matrix
    g.add("matrix_base", "uniform")
    g.bind("matrix_base", "outputcolor", vector(get("matrix_color", 3), 1.0).graph())
    g.add("speckle", "white_noise", seed=8)
    g.add("speckle_dots", "histogram_scan", {"input_1": "speckle"}, position=0.06, contrast=0.7)
    color_over(g, "matrix_speckled", "speckle_color", [0.35, 0.34, 0.33, 1.0], "matrix_base", mask="speckle_dots",
               opacitymult=0.6)
    g.add("matrix_clouds", "clouds_2", seed=19, scale=2.0)
    color_over(g, "matrix_color", "matrix_tone", [0.9, 0.89, 0.87, 1.0], "matrix_speckled", mask="matrix_clouds",
               blendingmode=3, opacitymult=0.5)

    g.add("chips_on_matrix", "blend", {"source": "chip_colors_grain", "destination": "matrix_color",
                                       "opacity": "chip_mask"})
    g.add("basecolor", "blend", {"source": "chips_on_matrix", "destination": "matrix_color"})
    g.bind("basecolor", "opacitymult", get("chip_contrast").graph())

    # pores
    g.add("pore_spots", "white_noise", seed=41)
    g.add("pores_mask", "histogram_scan", {"input_1": "pore_spots"}, contrast=0.8)
    g.bind("pores_mask", "position", (0.02 * get("pores")).graph())
    g.add("pores_blur", "blur", {"input1": "pores_mask"}, intensity=0.5)

    # roughness
    g.add("rough_base", "histogram_range", {"input": "chip_mask"}, range=0.08)
    g.bind("rough_base", "position", get("roughness").graph())
    g.add("rough_matrix", "blend", {"source": "matrix_clouds", "destination": "rough_base"},
          blendingmode=4, opacitymult=0.06)
    g.add("roughness", "blend", {"source": "pores_blur", "destination": "rough_matrix"},
          blendingmode=1, opacitymult=0.4)
    constant_map(g, "metallic", 0.0)

    # height
    g.add("chip_height", "histogram_range", {"input": "chip_mask"}, range=0.04, position=0.5)
    g.add("height", "blend", {"source": "pores_blur", "destination": "chip_height"}, blendingmode=2,
          opacitymult=0.5)
    g.add("normal", "normal", {"input1": "height"})
    g.bind("normal", "intensity", get("normal_intensity").graph())

    set_material_outputs(g)
    return g


FAMILY = "stone"

SAMPLE_RANGES = {
    "exposed.matrix_color": ([0.35, 0.33, 0.3], [0.92, 0.9, 0.88]),
    "exposed.chip_density": (0.3, 0.9),
    "exposed.chip_contrast": (0.4, 1.0),
    "exposed.roughness": (0.1, 0.45),
    "exposed.pores": (0.0, 1.0),
    "exposed.normal_intensity": (0.3, 2.0),
    "chips_large.scale": (0.6, 1.2),
    "chips_small.scale": (0.4, 1.0),
    "chips_large_warp.intensity": (0.4, 2.5),
}
