"""Material: hot-dip galvanized steel: dull grey zinc spangle with patches of white oxide.

Structure
- Spangle: zinc freezes into crystal grains a few centimetres across, each with its own sheen.
  A Voronoi mosaic of random levels (Cells 4, about 7 grains per sample width) gives one value per
  grain; a small noise warp makes the grain boundaries irregular instead of straight polygon edges.
- Crystal texture: inside a grain the dendrites run in one direction. Fine white noise smeared by
  directional blurs at three angles gives three feathery textures; the grain value picks one per
  grain (two histogram-scan masks), so neighbouring grains show different grain directions.
- Height: almost flat (zinc coating): the feathery texture and a faint step at the grain value,
  plus soft sheet waviness; normal from it at low intensity.
- Colour: the exposed zinc grey, each grain a little lighter or darker (spangle contrast), with the
  white rust (zinc oxide / carbonate) as powdery off-white patches from a grunge map, denser
  where a cloud noise says the sheet stayed wet.
- Roughness: the key of the spangle look: each grain at its own roughness around the exposed
  value (spangle contrast sets the spread), feather texture on top; white rust is very rough.
  Metallic: 1 on zinc, 0 under the white rust (a mineral crust).

Exposed parameters
- ``zinc_color`` (float3): the coating's grey (fresh bright zinc to dull weathered grey).
- ``spangle_contrast``: how different the grains look in sheen and brightness.
- ``roughness``: mean roughness of the zinc.
- ``white_rust``: amount of white oxide patches.
- ``crystal_texture``: strength of the feathery dendrite texture inside each grain.
"""
from __future__ import annotations

from blender_match.library.authoring import (
    ADD_SUB,
    MULTIPLY,
    SUBTRACT,
    color_over,
    gradient_over,
    set_material_outputs,
)
from blender_match.library.expressions import get, lerp, vector
from blender_match.translator.runtime import SbsGraph


def build() -> SbsGraph:
    g = SbsGraph("galvanized_metal")
    g.expose("zinc_color", (0.60, 0.61, 0.62), min=0.0, max=1.0)
    g.expose("spangle_contrast", 0.5, min=0.0, max=1.0)
    g.expose("roughness", 0.4, min=0.1, max=0.85)
    g.expose("white_rust", 0.2, min=0.0, max=1.0)
    g.expose("crystal_texture", 0.5, min=0.0, max=1.0)

    # ---- spangle grains ---------------------------------------------------------------------------
    g.add("grains_raw", "cells_4", seed=81, scale=7, disorder=0.8)
    g.add("edge_noise", "perlin_noise_1", seed=82, scale=16.0)
    g.add("grains", "warp", {"input1": "grains_raw", "inputgradient": "edge_noise"}, intensity=0.1)
    g.add("mask_a", "histogram_scan", {"input_1": "grains"}, position=0.35, contrast=0.97)
    g.add("mask_b", "histogram_scan", {"input_1": "grains"}, position=0.67, contrast=0.97)

    # ---- feathery dendrites in three directions ---------------------------------------------------
    g.add("speck", "white_noise", seed=83)
    g.add("feather_0", "dirmotionblur", {"input1": "speck"}, intensity=4.0, mblurangle=0.0)
    g.add("feather_1", "dirmotionblur", {"input1": "speck"}, intensity=4.0, mblurangle=0.166)
    g.add("feather_2", "dirmotionblur", {"input1": "speck"}, intensity=4.0, mblurangle=0.333)
    g.add("feather_02", "blend", {"source": "feather_2", "destination": "feather_0", "opacity": "mask_b"})
    g.add("feather_all", "blend", {"source": "feather_1", "destination": "feather_02", "opacity": "mask_a"})
    g.add("feathers", "auto_levels", {"input": "feather_all"})
    g.add("feather_level", "histogram_range", {"input": "feathers"}, range=0.5, position=0.5)
    g.bind("feather_level", "range", lerp(0.0, 1.0, get("crystal_texture")).graph())

    # ---- white rust --------------------------------------------------------------------------------------
    g.add("wet_clouds", "clouds_1", seed=84, scale=2.0)
    g.add("rust_grunge", "grunge_map_001", seed=85, scale=3.0)
    g.add("rust_raw", "blend", {"source": "wet_clouds", "destination": "rust_grunge"},
          blendingmode=MULTIPLY)
    g.add("rust_mask", "histogram_scan", {"input_1": "rust_raw"}, position=0.2, contrast=0.55)
    g.bind("rust_mask", "position", lerp(0.15, 0.85, get("white_rust")).graph())

    # ---- height and normal -------------------------------------------------------------------------------
    g.add("grain_step", "histogram_range", {"input": "grains"}, range=0.1, position=0.5)
    g.add("sheet_wave", "clouds_1", seed=86, scale=1.0)
    g.add("relief_feathers", "blend", {"source": "feather_level", "destination": "grain_step"},
          blendingmode=ADD_SUB, opacitymult=0.12)
    g.add("relief_waves", "blend", {"source": "sheet_wave", "destination": "relief_feathers"},
          blendingmode=ADD_SUB, opacitymult=0.25)
    g.add("height", "blend", {"source": "rust_mask", "destination": "relief_waves"},
          blendingmode=ADD_SUB, opacitymult=0.08)
    g.add("normal", "normal", {"input1": "height"}, intensity=0.7, inversedy=True)

    # ---- colour -----------------------------------------------------------------------------------------------
    g.add("zinc", "uniform", outputcolor=(0.60, 0.61, 0.62, 1.0))
    g.bind("zinc", "outputcolor", vector(get("zinc_color", 3), 1.0).graph())
    # zinc is nearly neutral: keep the colour's lightness, only a hint of its hue
    g.add("zinc_luma", "grayscaleconversion", {"input1": "zinc"})
    gradient_over(g, "zinc_neutral", "zinc_gray", "zinc_luma", [(0.0, (0.0, 0.0, 0.0)), (1.0, (1.0, 1.0, 1.0))], "zinc",
                  opacitymult=0.75)
    g.add("grain_feathered", "blend", {"source": "feather_level", "destination": "grains"},
          blendingmode=ADD_SUB, opacitymult=0.2)
    gradient_over(g, "zinc_grains", "grain_feather_tone", "grain_feathered",
                  [(0.0, (0.30, 0.30, 0.30)), (1.0, (0.70, 0.70, 0.71))], "zinc_neutral", blendingmode=9,
                  opacitymult=0.5)
    g.bind("zinc_grains", "opacitymult", lerp(0.0, 0.8, get("spangle_contrast")).graph())
    color_over(g, "basecolor", "oxide_color", (0.84, 0.84, 0.81, 1.0), "zinc_grains", mask="rust_mask", opacitymult=0.9)

    # ---- roughness and metallic -------------------------------------------------------------------------------
    g.add("grain_rough", "histogram_range", {"input": "grains"}, range=0.3, position=0.4)
    g.bind("grain_rough", "position", get("roughness").graph())
    g.bind("grain_rough", "range", lerp(0.02, 0.5, get("spangle_contrast")).graph())
    g.add("rough_feathered", "blend", {"source": "feather_level", "destination": "grain_rough"},
          blendingmode=ADD_SUB, opacitymult=0.12)
    g.add("rust_rough", "uniform", colorswitch=False, outputcolor=(0.92, 0.92, 0.92, 1.0))
    g.add("roughness", "blend", {"source": "rust_rough", "destination": "rough_feathered",
                                 "opacity": "rust_mask"})
    g.add("metal_full", "uniform", colorswitch=False, outputcolor=(1.0, 1.0, 1.0, 1.0))
    g.add("metallic", "blend", {"source": "rust_mask", "destination": "metal_full"},
          blendingmode=SUBTRACT, opacitymult=0.95)

    set_material_outputs(g)
    return g


FAMILY = "metal"

SAMPLE_RANGES = {
    "exposed.zinc_color": ((0.45, 0.46, 0.47), (0.78, 0.79, 0.80)),
    "exposed.spangle_contrast": (0.2, 0.9),
    "exposed.roughness": (0.25, 0.65),
    "exposed.white_rust": (0.0, 0.6),
    "exposed.crystal_texture": (0.2, 0.9),
    "grains_raw.disorder": (0.5, 1.0),
    "grains.intensity": (0.02, 0.12),
    "feather_0.intensity": (3.0, 10.0),
    "feather_1.intensity": (3.0, 10.0),
    "feather_2.intensity": (3.0, 10.0),
    "rust_grunge.scale": (2.0, 5.0),
    "normal.intensity": (0.3, 1.4),
    "grain_feather_tone.colors": ([0.27, 0.27, 0.27, 1.0, 0.66, 0.66, 0.67, 1.0],
                                  [0.33, 0.33, 0.33, 1.0, 0.74, 0.74, 0.75, 1.0]),
    "oxide_color.outputcolor": ([0.81, 0.81, 0.78, 1.0], [0.86, 0.86, 0.83, 1.0]),
    "zinc_neutral.opacitymult": (0.65, 0.9),
    "zinc_luma.channelsweights": ([0.33, 0.33, 0.33, 0.0], [0.33, 0.33, 0.33, 0.0]),
    "zinc_gray.colors": ([0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0], [0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0]),
}
