"""Asphalt: a worn road surface: dark bitumen binder packed with crushed-stone aggregate.

Structure
- Aggregate: two tile samplers of small angular stones (pyramids, random position, rotation,
  size and luminance), a dense fine layer and a sparser coarse one, combined by maximum and roughened
  by a fine noise; the binder (a soft noise level) fills between them, and the ``wear`` parameter
  lowers the binder so more stone tops are exposed.
- Base colour: stones coloured through a light-grey / dark-grey / brownish palette by their random
  luminance, the binder a dark tint (exposed) lightened by wear and dust.
- Roughness: binder rough (worn bitumen), exposed stone tops a little smoother.
- Height: stones above the binder; normal from height (OpenGL) plus a fine grain detail normal.
- Metallic 0; ambient occlusion from height.

Exposed parameters
- ``binder_color`` (float3, sRGB): colour of the bitumen binder.
- ``stone_size``: size of the aggregate stones.
- ``wear``: how much aggregate is exposed and how faded the binder is.
- ``roughness``: the mean roughness.
- ``relief``: the strength of the normal map.
"""
from __future__ import annotations

from blender_match.library.authoring import OUR_OCCLUSION, color_over, constant_map
from blender_match.library.expressions import clamp, get, lerp, vector
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("asphalt")
    g.expose("binder_color", [0.16, 0.16, 0.16], min=0.0, max=1.0)
    g.expose("stone_size", 1.0, min=0.5, max=1.5)
    g.expose("wear", 0.6, min=0.0, max=1.0)
    g.expose("roughness", 0.85, min=0.5, max=1.0)
    g.expose("relief", 0.5, min=0.0, max=1.0)
    size = get("stone_size")
    wear = get("wear")

    # ---- generators -------------------------------------------------------------------------
    g.add("fine_stones", "tile_sampler", seed=61, x_amount=40, y_amount=40, pattern=7, scale=1.3,
          position_random=0.5, rotation_random=0.5, scale_random=0.6, luminance_random=0.3, mask_random=0.05)
    g.bind("fine_stones", "scale", clamp(size * 1.3, 0.0, 2.0).graph())
    g.add("coarse_stones", "tile_sampler", seed=62, x_amount=16, y_amount=16, pattern=7, scale=1.1,
          position_random=0.5, rotation_random=0.5, scale_random=0.5, luminance_random=0.3, mask_random=0.35)
    g.bind("coarse_stones", "scale", clamp(size * 1.1, 0.0, 2.0).graph())
    g.add("binder_noise", "clouds_2", seed=63, scale=6.0)
    g.add("grain", "white_noise", seed=64)
    g.add("tint_noise", "white_noise", seed=65)
    g.add("dust", "clouds_1", seed=66, scale=3.0)

    # ---- aggregate relief ---------------------------------------------------------------------------
    g.add("stones", "blend", {"source": "coarse_stones", "destination": "fine_stones"}, blendingmode=5)
    g.add("grain_soft", "blur", {"input1": "grain"}, intensity=0.5)
    g.add("stones_rough", "blend", {"source": "grain_soft", "destination": "stones"}, blendingmode=4,
          opacitymult=0.12)
    # the binder level: a soft noise; wear lowers it to expose more stone
    g.add("binder_level", "histogram_range", {"input": "binder_noise"}, range=0.25, position=0.25)
    g.bind("binder_level", "position", lerp(0.42, 0.1, wear).graph())
    g.add("height", "blend", {"source": "stones_rough", "destination": "binder_level"}, blendingmode=5)
    g.set_output("height", "height")
    # exposed stone mask: where the stones stand above the binder
    g.add("exposed_diff", "blend", {"source": "binder_level", "destination": "stones_rough"}, blendingmode=2)
    g.add("stone_mask", "histogram_scan", {"input_1": "exposed_diff"}, position=0.96, contrast=0.8)

    # ---- normal ---------------------------------------------------------------------------------
    g.add("n_main", "normal", {"input1": "height"}, intensity=5.0, inversedy=True, input2alpha=False)
    g.bind("n_main", "intensity", lerp(0.5, 10.0, get("relief")).graph())
    g.add("n_grain", "normal", {"input1": "grain_soft"}, intensity=0.6, inversedy=True, input2alpha=False)
    g.add("n_out", "normal_combine", {"input": "n_main", "input_1": "n_grain"})
    g.set_output("normal", "n_out")

    # ---- colour -----------------------------------------------------------------------------------
    # per-stone tone: stone luminance mixed with a per-pixel-cluster noise so stones differ in hue
    g.add("tint_soft", "blur", {"input1": "tint_noise"}, intensity=0.7)
    g.add("stone_tone", "blend", {"source": "tint_soft", "destination": "stones"}, blendingmode=0, opacitymult=0.75)
    g.add("stone_col", "gradient", {"input1": "stone_tone"},
          positions=[0.0, 0.3, 0.55, 0.75, 1.0],
          colors=[0.10, 0.10, 0.11, 1.0, 0.30, 0.30, 0.31, 1.0, 0.50, 0.49, 0.48, 1.0,
                  0.46, 0.38, 0.31, 1.0, 0.75, 0.74, 0.72, 1.0])
    g.add("binder_tint", "uniform", outputcolor=[0.16, 0.16, 0.16, 1.0])
    g.bind("binder_tint", "outputcolor", vector(get("binder_color", 3), 1.0).graph())
    g.add("dust_mask", "histogram_scan", {"input_1": "dust"}, position=0.5, contrast=0.1)
    color_over(g, "binder_dusty", "dust_color", [0.42, 0.40, 0.37, 1.0], "binder_tint", mask="dust_mask",
               blendingmode=0, opacitymult=0.3)
    g.bind("binder_dusty", "opacitymult", lerp(0.05, 0.5, wear).graph())
    g.add("col_out", "blend", {"source": "stone_col", "destination": "binder_dusty", "opacity": "stone_mask"},
          blendingmode=0)
    g.set_output("basecolor", "col_out")

    # ---- roughness ------------------------------------------------------------------------------
    g.add("r_base", "histogram_range", {"input": "grain_soft"}, range=0.1, position=0.85)
    g.bind("r_base", "position", get("roughness").graph())
    g.add("r_out", "blend", {"source": "stone_mask", "destination": "r_base"}, blendingmode=2, opacitymult=0.15)
    g.set_output("roughness", "r_out")

    # ---- metallic, AO ---------------------------------------------------------------------------
    constant_map(g, "metal", 0.0)
    g.set_output("metallic", "metal")
    g.add("ao", "ambient_occlusion_2", {"source": "height"}, height_depth=0.15, spreading=0.05,
          model=OUR_OCCLUSION)
    g.set_output("ambientocclusion", "ao:ambient_occlusion")
    return g


FAMILY = "ground"

SAMPLE_RANGES = {
    "exposed.binder_color": ([0.06, 0.06, 0.06], [0.32, 0.31, 0.30]),
    "exposed.stone_size": (0.7, 1.3),
    "exposed.wear": (0.1, 1.0),
    "exposed.roughness": (0.7, 0.97),
    "exposed.relief": (0.25, 0.9),
    "stone_col.colors": ([0.08, 0.08, 0.08, 1.0, 0.25, 0.24, 0.23, 1.0, 0.42, 0.4, 0.38, 1.0,
                          0.38, 0.3, 0.24, 1.0, 0.58, 0.56, 0.53, 1.0],
                         [0.28, 0.28, 0.28, 1.0, 0.46, 0.45, 0.44, 1.0, 0.66, 0.64, 0.62, 1.0,
                          0.62, 0.54, 0.46, 1.0, 0.86, 0.85, 0.83, 1.0]),
    "stone_tone.opacitymult": (0.2, 0.8),
    "coarse_stones.mask_random": (0.2, 0.9),
    "fine_stones.mask_random": (0.0, 0.5),
    "r_out.opacitymult": (0.0, 0.3),
}
