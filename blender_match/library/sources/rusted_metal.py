"""Rusted steel: dark mill-scale steel eaten by patches of flaky orange-brown rust, with pitting.

Structure: a rust mask from large clouds and a dirt map histogram-scanned by the rust amount
slider, broken up at its edges by fine fractal noise; a rust texture (fractal sum + crystal grain)
coloured by a gradient map (dark umber to orange) and tinted by the rust colour; pitting (sparse
spots) in the bare metal. Base colour and roughness switch between steel and rust by the mask;
metallic = 1 on steel, 0 on rust; height = raised, crusty rust over the pitted steel; normal from
height.

Exposed parameters: ``rust_amount``, ``rust_color`` (sRGB tint multiplied with the rust
gradient), ``rust_roughness``, ``metal_color`` (sRGB), ``metal_roughness``, ``pitting``,
``normal_intensity``.
"""
from blender_match.library.authoring import color_over, set_material_outputs
from blender_match.library.expressions import get, vector
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("rusted_metal")
    g.expose("rust_amount", 0.45, min=0.0, max=1.0)
    g.expose("rust_color", [1.0, 0.92, 0.85], min=0.0, max=1.0)
    g.expose("rust_roughness", 0.86, min=0.5, max=1.0)
    g.expose("metal_color", [0.47, 0.47, 0.48], min=0.0, max=1.0)
    g.expose("metal_roughness", 0.42, min=0.1, max=0.9)
    g.expose("pitting", 0.5, min=0.0, max=1.0)
    g.expose("normal_intensity", 2.0, min=0.0, max=6.0)

    # rust mask
    g.add("patch_clouds", "clouds_2", seed=21, scale=1.0, disorder=0.3)
    g.add("patch_dirt", "dirt_4", seed=9, scale=2.0)
    g.add("patch_mix", "blend", {"source": "patch_dirt", "destination": "patch_clouds"},
          blendingmode=9, opacitymult=0.55)
    g.add("edge_noise", "fractal_sum_1", seed=33, scale=4.0, roughness=0.6)
    g.add("patch_edges", "blend", {"source": "edge_noise", "destination": "patch_mix"},
          blendingmode=4, opacitymult=0.3)
    g.add("rust_mask", "histogram_scan", {"input_1": "patch_edges"}, contrast=0.75)
    g.bind("rust_mask", "position", (0.1 + 0.75 * get("rust_amount")).graph())
    g.add("rust_mask_soft", "blur", {"input1": "rust_mask"}, intensity=1.0)

    # rust texture
    g.add("rust_fractal", "fractal_sum_3", seed=6, scale=6.0, roughness=0.6)
    g.add("rust_grain", "crystal_1", seed=14, scale=12.0)
    g.add("rust_detail", "blend", {"source": "rust_grain", "destination": "rust_fractal"},
          blendingmode=9, opacitymult=0.5)
    g.add("rust_gradient", "gradient", {"input1": "rust_detail"}, positions=[0.0, 0.35, 0.7, 1.0],
          colors=[0.17, 0.07, 0.03, 1.0, 0.33, 0.13, 0.05, 1.0,
                  0.52, 0.23, 0.08, 1.0, 0.66, 0.36, 0.15, 1.0])
    g.add("rust_tint", "uniform")
    g.bind("rust_tint", "outputcolor", vector(get("rust_color", 3), 1.0).graph())
    g.add("rust_color", "blend", {"source": "rust_tint", "destination": "rust_gradient"}, blendingmode=3)
    color_over(g, "rust_color_edges", "rust_dark_edges", [0.45, 0.36, 0.3, 1.0], "rust_color", mask="edge_noise",
               blendingmode=3, opacitymult=0.4)

    # steel
    g.add("steel_noise", "clouds_3", seed=3, scale=4.0)
    g.add("steel_base", "uniform")
    g.bind("steel_base", "outputcolor", vector(get("metal_color", 3), 1.0).graph())
    color_over(g, "steel_color", "steel_tone", [0.8, 0.8, 0.82, 1.0], "steel_base", mask="steel_noise", blendingmode=3,
               opacitymult=0.5)
    g.add("pits_spots", "bnw_spots_2", seed=40, scale=8.0)
    g.add("pits", "histogram_scan", {"input_1": "pits_spots"}, contrast=0.7)
    g.bind("pits", "position", (0.2 * get("pitting")).graph())

    g.add("basecolor", "blend", {"source": "rust_color_edges", "destination": "steel_color",
                                 "opacity": "rust_mask_soft"})

    # roughness
    g.add("steel_rough", "histogram_range", {"input": "steel_noise"}, range=0.15)
    g.bind("steel_rough", "position", get("metal_roughness").graph())
    g.add("steel_rough_pits", "blend", {"source": "pits", "destination": "steel_rough"},
          blendingmode=1, opacitymult=0.25)
    g.add("rust_rough", "histogram_range", {"input": "rust_detail"}, range=0.12)
    g.bind("rust_rough", "position", get("rust_roughness").graph())
    g.add("roughness", "blend", {"source": "rust_rough", "destination": "steel_rough_pits",
                                 "opacity": "rust_mask_soft"})

    # metallic
    g.add("steel_one", "uniform", colorswitch=False, outputcolor=[1.0, 1.0, 1.0, 1.0])
    g.add("rust_zero", "uniform", colorswitch=False, outputcolor=[0.0, 0.0, 0.0, 1.0])
    g.add("metallic", "blend", {"source": "rust_zero", "destination": "steel_one", "opacity": "rust_mask"})

    # height
    g.add("rust_crust", "histogram_range", {"input": "rust_detail"}, range=0.3, position=0.62)
    g.add("steel_height", "blend", {"source": "pits", "destination": "steel_noise"}, blendingmode=2,
          opacitymult=0.5)
    g.add("steel_height_flat", "histogram_range", {"input": "steel_height"}, range=0.12, position=0.4)
    g.add("height", "blend", {"source": "rust_crust", "destination": "steel_height_flat",
                              "opacity": "rust_mask_soft"})
    g.add("normal", "normal", {"input1": "height"})
    g.bind("normal", "intensity", get("normal_intensity").graph())

    set_material_outputs(g)
    return g


FAMILY = "metal"

SAMPLE_RANGES = {
    "exposed.rust_amount": (0.15, 0.85),
    "exposed.rust_color": ([0.8, 0.7, 0.6], [1.0, 1.0, 1.0]),
    "exposed.rust_roughness": (0.7, 0.98),
    "exposed.metal_color": ([0.35, 0.35, 0.36], [0.6, 0.6, 0.62]),
    "exposed.metal_roughness": (0.25, 0.65),
    "exposed.pitting": (0.0, 1.0),
    "exposed.normal_intensity": (0.8, 4.0),
    "patch_clouds.scale": (1.0, 3.0),
    "patch_mix.opacitymult": (0.2, 0.9),
    "rust_mask.contrast": (0.5, 0.9),
    "steel_one.outputcolor": (1.0, 1.0),
    "rust_zero.outputcolor": (0.0, 0.0),
}
