"""Material graphs bundled with blender_match as Python builders, by name.

``example`` is a 50-node production-style material (worn stone tiles: a tile generator, eight
noises, warps, blurs, colour gradients, a normal combine, ambient occlusion): the bundled example
the README's first command renders, and the graph ``blender-match bench nodes`` measures.
"""
from __future__ import annotations

from typing import Callable

from .diffmat import MaterialGraph
from .errors import OptionError
from .library.authoring import ADD, ADD_SUB, MAX, MULTIPLY, OVERLAY, SCREEN, SUBTRACT, gradient_keys


def _rgba(r: float, g: float, b: float) -> dict:
    return {"outputcolor": (r, g, b, 1.0)}


def worn_stone_tiles() -> MaterialGraph:
    g = MaterialGraph("worn_stone_tiles")
    # generators
    g.add("tiles", "tile_generator", x_amount=4, y_amount=4, pattern=1, interstice=(0.04, 0.04),
          luminance_random=0.25, softness=0.15, offset=0.5)
    g.add("perlin", "perlin_noise_zoom", scale=12.0, seed=1)
    g.add("clouds", "clouds_2", seed=2)
    g.add("spots", "bnw_spots_2", seed=3)
    g.add("moisture", "moisture_noise", seed=4)
    g.add("grunge", "grunge_map_012", seed=5)
    g.add("cells", "cells_1", seed=6)
    g.add("fractal", "fractal_sum_base", seed=7)
    g.add("dirt", "dirt_1", seed=8)
    # height
    g.add("perlin_zoom", "transformation", {"input1": "perlin"}, matrix22=(2.0, 0.0, 0.0, 2.0))
    g.add("tiles_warp", "warp", {"input1": "tiles", "inputgradient": "perlin"}, intensity=1.5)
    g.add("tiles_slope", "slope_blur_grayscale", {"source": "tiles_warp", "effect": "clouds"}, intensity=3.0)
    g.add("tiles_soft", "blur_hq_grayscale", {"source": "tiles_slope"}, intensity=1.0)
    g.add("edges", "edge_detect", {"input": "tiles_warp"})
    g.add("cracks", "histogram_scan", {"input_1": "cells"}, position=0.2, contrast=0.8)
    g.add("cracks_inv", "invert_grayscale", {"source": "cracks"})
    g.add("surface", "blend", {"source": "fractal", "destination": "tiles_soft"},
          blendingmode=MULTIPLY, opacitymult=0.3)
    g.add("pitted", "blend", {"source": "spots", "destination": "surface"}, blendingmode=SUBTRACT, opacitymult=0.1)
    g.add("cracked", "blend", {"source": "cracks_inv", "destination": "pitted"},
          blendingmode=MULTIPLY, opacitymult=0.5)
    g.add("height_levels", "levels", {"input1": "cracked"}, levelinlow=(0.05, 0.05, 0.05, 0.0))
    g.add("height", "histogram_range", {"input": "height_levels"}, range=0.8, position=0.5)
    # normal
    g.add("normal_main", "normal", {"input1": "height"}, intensity=4.0, inversedy=True)
    g.add("grunge_tiled", "safe_transform_grayscale", {"input": "grunge"}, tile=2)
    g.add("normal_detail", "normal", {"input1": "grunge_tiled"}, intensity=1.0, inversedy=True)
    g.add("normal_mix", "normal_combine", {"input": "normal_main", "input_1": "normal_detail"})
    g.add("ao", "ambient_occlusion_2", {"source": "height"})
    # base colour
    g.add("stone", "gradient", {"input1": "height"},
          **gradient_keys([(0.0, (0.18, 0.16, 0.14)), (0.6, (0.52, 0.47, 0.40)), (1.0, (0.74, 0.69, 0.60))]))
    g.add("tint", "gradient", {"input1": "clouds"},
          **gradient_keys([(0.0, (0.45, 0.42, 0.38)), (1.0, (0.62, 0.55, 0.47))]))
    g.add("tint_warp", "directionalwarp", {"input1": "tint", "inputintensity": "perlin_zoom"}, intensity=4.0)
    g.add("tinted", "blend", {"source": "tint_warp", "destination": "stone"}, blendingmode=OVERLAY, opacitymult=0.4)
    g.add("dirt_mask", "levels", {"input1": "dirt"}, levelinlow=(0.3, 0.3, 0.3, 0.0))
    g.add("dirt_color", "uniform", **_rgba(0.20, 0.16, 0.11))
    g.add("dirty", "blend", {"source": "dirt_color", "destination": "tinted", "opacity": "dirt_mask"}, opacitymult=0.6)
    g.add("edge_mask", "levels", {"input1": "edges"}, levelouthigh=(0.5, 0.5, 0.5, 1.0))
    g.add("edge_color", "uniform", **_rgba(0.80, 0.77, 0.70))
    g.add("worn_edges", "blend", {"source": "edge_color", "destination": "dirty", "opacity": "edge_mask"},
          blendingmode=SCREEN, opacitymult=0.5)
    g.add("ao_rgb", "gradient", {"input1": "ao"}, **gradient_keys([(0.0, (0.0, 0.0, 0.0)), (1.0, (1.0, 1.0, 1.0))]))
    g.add("occluded", "blend", {"source": "ao_rgb", "destination": "worn_edges"},
          blendingmode=MULTIPLY, opacitymult=0.7)
    g.add("graded", "hsl", {"input1": "occluded"}, saturation=0.45, luminosity=0.52)
    g.add("basecolor", "sharpen", {"input1": "graded"}, intensity=0.5)
    # roughness
    g.add("rough_base", "levels", {"input1": "moisture"}, leveloutlow=(0.55, 0.55, 0.55, 0.0),
          levelouthigh=(0.8, 0.8, 0.8, 1.0))
    g.add("rough_grunge", "blend", {"source": "grunge", "destination": "rough_base"},
          blendingmode=ADD_SUB, opacitymult=0.3)
    g.add("rough_dirt", "blend", {"source": "dirt_mask", "destination": "rough_grunge"},
          blendingmode=MAX, opacitymult=0.5)
    g.add("rough_cracks", "blend", {"source": "cracks", "destination": "rough_dirt"}, blendingmode=ADD, opacitymult=0.2)
    g.add("color_lum", "grayscaleconversion", {"input1": "graded"})
    g.add("rough_color", "blend", {"source": "color_lum", "destination": "rough_cracks"},
          blendingmode=SUBTRACT, opacitymult=0.1)
    g.add("roughness", "levels", {"input1": "rough_color"}, leveloutlow=(0.35, 0.35, 0.35, 0.0),
          levelouthigh=(0.9, 0.9, 0.9, 1.0))
    # metallic: a few mica flecks
    g.add("flecks", "histogram_scan", {"input_1": "spots"}, position=0.01, contrast=0.95)
    g.add("flecks_soft", "blur", {"input1": "flecks"}, intensity=0.5)
    g.add("metallic", "levels", {"input1": "flecks_soft"}, levelouthigh=(0.3, 0.3, 0.3, 1.0))
    for usage, node in (("basecolor", "basecolor"), ("normal", "normal_mix"), ("roughness", "roughness"),
                        ("metallic", "metallic"), ("height", "height"), ("ambientocclusion", "ao")):
        g.set_output(usage, node)
    return g


BUNDLED: dict[str, tuple[Callable[[], MaterialGraph], str]] = {
    "example": (worn_stone_tiles, "worn stone tiles, 50 nodes (the bundled example)"),
}


def build(name: str) -> MaterialGraph:
    """A fresh MaterialGraph of bundled graph ``name``."""
    if name not in BUNDLED:
        raise OptionError(f"{name}: no such bundled graph ({', '.join(sorted(BUNDLED))})")
    return BUNDLED[name][0]()
