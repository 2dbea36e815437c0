"""Ground: bare soil strewn with gravel and small pebbles.

Structure
- Soil: a large clouds undulation, crumbly clods (black-and-white spots) and a fine grain.
- Pebbles: two tile samplers (larger and smaller rounded paraboloid stones, random position,
  rotation, size and luminance), warped by a noise so the outlines are irregular; the pebbles sit
  on the soil (max blend). How many are shown is the exposed ``gravel`` amount (mask random).
- Base colour: the exposed soil colour varied by the soil relief; pebbles coloured by their random
  luminance through a grey / beige / rust stone palette; moisture darkens the soil.
- Roughness: soil almost fully rough, pebbles smoother; moisture lowers the soil roughness.
- Normal: from the height (OpenGL) combined with a soil grain detail normal. Metallic 0.

Exposed parameters
- ``soil_color`` (float3, sRGB): the dry soil colour.
- ``gravel``: amount of pebbles (0 bare soil, 1 densely covered).
- ``pebble_size``: size of the pebbles.
- ``moisture``: wetness (darker, less rough soil).
- ``relief``: the strength of the normal map.
"""
from __future__ import annotations

from blender_match.library.authoring import OUR_OCCLUSION, color_over, constant_map
from blender_match.library.expressions import clamp, get, lerp, vector
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("ground")
    g.expose("soil_color", [0.36, 0.28, 0.21], min=0.0, max=1.0)
    g.expose("gravel", 0.5, min=0.0, max=1.0)
    g.expose("pebble_size", 1.0, min=0.5, max=1.5)
    g.expose("moisture", 0.2, min=0.0, max=1.0)
    g.expose("relief", 0.6, min=0.0, max=1.0)
    gravel = get("gravel")
    size = get("pebble_size")
    moisture = get("moisture")

    # ---- generators -------------------------------------------------------------------------
    g.add("big", "clouds_2", seed=51, scale=3.0)
    g.add("clods", "bnw_spots_1", seed=52, scale=10.0)
    g.add("grain", "gaussian_noise", seed=53, scale=2.0)
    g.add("pebbles_l", "tile_sampler", seed=54, x_amount=6, y_amount=6, pattern=3, scale=0.9,
          size_xy=[1.0, 0.75], position_random=0.5, rotation_random=0.5, scale_random=0.5,
          luminance_random=0.25, mask_random=0.5)
    g.bind("pebbles_l", "scale", clamp(size * 0.9, 0.0, 2.0).graph())
    g.bind("pebbles_l", "mask_random", lerp(0.95, 0.2, gravel).graph())
    g.add("pebbles_s", "tile_sampler", seed=55, x_amount=14, y_amount=14, pattern=3, scale=0.8,
          size_xy=[1.0, 0.7], position_random=0.5, rotation_random=0.5, scale_random=0.6,
          luminance_random=0.25, mask_random=0.4)
    g.bind("pebbles_s", "scale", clamp(size * 0.8, 0.0, 2.0).graph())
    g.bind("pebbles_s", "mask_random", lerp(0.9, 0.05, gravel).graph())

    # ---- soil -------------------------------------------------------------------------------------
    g.add("clods_soft", "blur", {"input1": "clods"}, intensity=1.0)
    g.add("soil", "blend", {"source": "clods_soft", "destination": "big"}, blendingmode=4, opacitymult=0.3)
    g.add("soil_g", "blend", {"source": "grain", "destination": "soil"}, blendingmode=4, opacitymult=0.15)
    g.add("soil_h", "histogram_range", {"input": "soil_g"}, range=0.35, position=0.3)

    # ---- pebbles ------------------------------------------------------------------------------------
    g.add("pebbles", "blend", {"source": "pebbles_s", "destination": "pebbles_l"}, blendingmode=5)
    g.add("pebbles_w", "warp", {"input1": "pebbles", "inputgradient": "big"}, intensity=0.05)
    g.add("peb_mask", "histogram_scan", {"input_1": "pebbles_w"}, position=0.97, contrast=0.85)
    g.add("peb_h", "histogram_range", {"input": "pebbles_w"}, range=0.8, position=0.55)
    g.add("peb_h_m", "blend", {"source": "peb_h", "destination": "soil_h", "opacity": "peb_mask"},
          blendingmode=5)
    g.set_output("height", "peb_h_m")

    # ---- normal ---------------------------------------------------------------------------------
    g.add("n_main", "normal", {"input1": "peb_h_m"}, intensity=8.0, inversedy=True, input2alpha=False)
    g.bind("n_main", "intensity", lerp(1.0, 16.0, get("relief")).graph())
    g.add("n_grain", "normal", {"input1": "grain"}, intensity=1.2, inversedy=True, input2alpha=False)
    g.add("n_out", "normal_combine", {"input": "n_main", "input_1": "n_grain"})
    g.set_output("normal", "n_out")

    # ---- colour -------------------------------------------------------------------------------------
    g.add("soil_var", "gradient", {"input1": "soil_g"},
          positions=[0.0, 0.5, 1.0],
          colors=[0.62, 0.60, 0.60, 1.0, 0.88, 0.86, 0.84, 1.0, 1.0, 0.98, 0.94, 1.0])
    g.add("soil_tint", "uniform", outputcolor=[0.36, 0.28, 0.21, 1.0])
    g.bind("soil_tint", "outputcolor", vector(get("soil_color", 3), 1.0).graph())
    g.add("soil_col", "blend", {"source": "soil_var", "destination": "soil_tint"}, blendingmode=3)
    color_over(g, "soil_wet", "wet", [0.55, 0.52, 0.5, 1.0], "soil_col", blendingmode=3, opacitymult=0.2)
    g.bind("soil_wet", "opacitymult", moisture.graph())
    g.add("peb_lum", "blend", {"source": "big", "destination": "pebbles_w"}, blendingmode=4, opacitymult=0.6)
    g.add("peb_col", "gradient", {"input1": "peb_lum"},
          positions=[0.0, 0.35, 0.6, 0.8, 1.0],
          colors=[0.30, 0.29, 0.28, 1.0, 0.45, 0.43, 0.40, 1.0, 0.62, 0.56, 0.48, 1.0,
                  0.55, 0.42, 0.32, 1.0, 0.76, 0.73, 0.68, 1.0])
    g.add("col_out", "blend", {"source": "peb_col", "destination": "soil_wet", "opacity": "peb_mask"},
          blendingmode=0)
    g.set_output("basecolor", "col_out")

    # ---- roughness ------------------------------------------------------------------------------
    g.add("r_soil", "histogram_range", {"input": "grain"}, range=0.08, position=0.93)
    g.bind("r_soil", "position", lerp(0.95, 0.6, moisture).graph())
    g.add("r_peb", "uniform", outputcolor=[0.62, 0.62, 0.62, 1.0], colorswitch=False)
    g.add("r_out", "blend", {"source": "r_peb", "destination": "r_soil", "opacity": "peb_mask"}, blendingmode=0)
    g.set_output("roughness", "r_out")

    # ---- metallic, AO ---------------------------------------------------------------------------
    constant_map(g, "metal", 0.0)
    g.set_output("metallic", "metal")
    g.add("ao", "ambient_occlusion_2", {"source": "peb_h_m"}, height_depth=0.2, spreading=0.1,
          model=OUR_OCCLUSION)
    g.set_output("ambientocclusion", "ao:ambient_occlusion")
    return g


FAMILY = "ground"

SAMPLE_RANGES = {
    "exposed.soil_color": ([0.28, 0.21, 0.15], [0.46, 0.37, 0.28]),
    "exposed.gravel": (0.1, 0.95),
    "exposed.pebble_size": (0.6, 1.4),
    "exposed.moisture": (0.0, 0.8),
    "exposed.relief": (0.3, 1.0),
    "soil.opacitymult": (0.1, 0.5),
    "pebbles_l.luminance_random": (0.0, 0.5),
    "pebbles_s.luminance_random": (0.0, 0.5),
    "pebbles_w.intensity": (0.0, 0.12),
    "r_peb.outputcolor": ([0.45, 0.45, 0.45, 1.0], [0.8, 0.8, 0.8, 1.0]),
}
