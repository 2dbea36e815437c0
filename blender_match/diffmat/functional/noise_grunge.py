"""Substance's Dirt 1-6 and Grunge Map 001-015 generators as rows of the recipe table of
``noise_generators`` (see ``Recipe``): each is a distinct combination of the same primitives,
a base fractal (value / gradient lattice, plain / ridged / billowed, isotropic or streaked),
an optional detail layer (fine speckle, Gaussian spots, cellular pits or cellular seams), an
optional domain warp and a tone curve. Dirt maps take ``scale`` and ``disorder``; grunge maps add
``balance`` (brightness offset of the tone curve, 0.5 = the map's own look), ``contrast``
(steepness, 0.5 = the map's own look) and ``invert`` (1 - the map: production files switch it on for
Grunge Maps 006, 007, 010, 012 and 013).

Substance's documentation calls the Dirt family "grainy" (Dirt 1, 2, 4 and 5 are each "a variation
of the grainy Dirt noises"): no dirt here is warped or ridged into swirls. The rest of each recipe
(cells, octaves, detail) is ours: the generators' own looks are not published.

Per node (cells at scale 1, octaves x roughness, mode, detail x weight, warp, tone):
dirt_1  grainy smudges: value 2 cells 7x0.6 + speckle 0.4, darkish
dirt_2  puffy grime: gradient 4 cells 6x0.55 billow + cellular pits 0.4
dirt_3  grainy crusts: gradient 2 cells 6x0.6 + fine speckle 0.45
dirt_4  sparse dust: gradient 1 cell 8x0.65 + speckle 0.5, bright, high contrast
dirt_5  grainy mottle: gradient 2 cells 6x0.6 + fine speckle 0.4
dirt_6  dried cracks: gradient 4 cells 5x0.5 ridged + cellular seams 0.5
grunge_map_001 fine grain: value 4 cells 8x0.7 + speckle 0.4, contrasted
grunge_map_002 cracked: gradient 2 cells 7x0.6 ridged, warp 0.04
grunge_map_003 blotches: value 8 cells 5x0.5 billow + spots 0.5
grunge_map_004 scratchy streaks: gradient 2 cells 6x0.6 stretched (1, 6)
grunge_map_005 cellular stains: value 2 cells 7x0.55 + cellular seams 0.6
grunge_map_006 swirled billows: gradient 4 cells 6x0.65 billow, warp 0.08
grunge_map_007 rough ridges: value 1 cell 8x0.6 ridged + speckle 0.3, high contrast
grunge_map_008 dense grain: gradient 8 cells 5x0.75, very contrasted
grunge_map_009 vertical wash: value 2 cells 6x0.6 stretched (4, 1), warp 0.03
grunge_map_010 pitted ridges: gradient 4 cells 6x0.5 ridged + cellular pits 0.5
grunge_map_011 splotches: value 2 cells 7x0.6 billow + spots 0.4, warp 0.05
grunge_map_012 organic grunge: gradient 2 cells 8x0.62 + speckle 0.25, darkish, contrasted
grunge_map_013 warped cells: value 4 cells 6x0.55 + cellular seams 0.4, warp 0.1
grunge_map_014 horizontal ridges: gradient 1 cell 6x0.6 ridged stretched (6, 1)
grunge_map_015 pitted grain: value 1 cell 9x0.7 + cellular pits 0.3, very contrasted
"""
from __future__ import annotations

from .noise_generators import Recipe, make_recipe_generator

__all__: list[str] = []

_DIRT = (1, 32, 1)
GRUNGE_RECIPES: dict[str, tuple[Recipe, tuple, tuple]] = {
    "dirt_1": (Recipe(kind="value", cells=2, octaves=7, roughness=0.6, detail="speckle", detail_cells=16,
                      detail_weight=0.4, gain=1.0, offset=-0.2), _DIRT, ()),
    "dirt_2": (Recipe(cells=4, octaves=6, roughness=0.55, mode="billow", detail="cells", detail_cells=16,
                      detail_weight=0.4, gain=1.2), _DIRT, ()),
    "dirt_3": (Recipe(cells=2, octaves=6, roughness=0.6, detail="speckle", detail_cells=32,
                      detail_weight=0.45, gain=1.1), _DIRT, ()),
    "dirt_4": (Recipe(cells=1, octaves=8, roughness=0.65, detail="speckle", detail_cells=32, detail_weight=0.5,
                      gain=1.4, offset=0.3), _DIRT, ()),
    "dirt_5": (Recipe(cells=2, octaves=6, roughness=0.6, detail="speckle", detail_cells=32,
                      detail_weight=0.4, gain=1.0), _DIRT, ()),
    "dirt_6": (Recipe(cells=4, octaves=5, roughness=0.5, mode="ridged", detail="edges", detail_cells=8,
                      detail_weight=0.5, gain=1.3), _DIRT, ()),
}
_TONE = ("balance", "contrast", "invert")
_GRUNGE = (1, 16, 1)
GRUNGE_RECIPES.update({
    "grunge_map_001": (Recipe(kind="value", cells=4, octaves=8, roughness=0.7, detail="speckle", detail_cells=16,
                              detail_weight=0.4, gain=1.5), _GRUNGE, _TONE),
    "grunge_map_002": (Recipe(cells=2, octaves=7, roughness=0.6, mode="ridged", warp=0.04, gain=1.2), _GRUNGE, _TONE),
    "grunge_map_003": (Recipe(kind="value", cells=8, octaves=5, roughness=0.5, mode="billow", detail="spots",
                              detail_cells=16, detail_weight=0.5, gain=1.3), _GRUNGE, _TONE),
    "grunge_map_004": (Recipe(cells=2, aspect=(1, 6), octaves=6, roughness=0.6, gain=1.2), _GRUNGE, _TONE),
    "grunge_map_005": (Recipe(kind="value", cells=2, octaves=7, roughness=0.55, detail="edges", detail_cells=8,
                              detail_weight=0.6, gain=1.4), _GRUNGE, _TONE),
    "grunge_map_006": (Recipe(cells=4, octaves=6, roughness=0.65, mode="billow", warp=0.08, gain=1.3), _GRUNGE, _TONE),
    "grunge_map_007": (Recipe(kind="value", cells=1, octaves=8, roughness=0.6, mode="ridged", detail="speckle",
                              detail_cells=32, detail_weight=0.3, gain=1.6), _GRUNGE, _TONE),
    "grunge_map_008": (Recipe(cells=8, octaves=5, roughness=0.75, gain=2.0), _GRUNGE, _TONE),
    "grunge_map_009": (Recipe(kind="value", cells=2, aspect=(4, 1), octaves=6, roughness=0.6, warp=0.03, gain=1.2),
                       _GRUNGE, _TONE),
    "grunge_map_010": (Recipe(cells=4, octaves=6, roughness=0.5, mode="ridged", detail="cells", detail_cells=12,
                              detail_weight=0.5, gain=1.2), _GRUNGE, _TONE),
    "grunge_map_011": (Recipe(kind="value", cells=2, octaves=7, roughness=0.6, mode="billow", detail="spots",
                              detail_cells=24, detail_weight=0.4, warp=0.05, gain=1.1), _GRUNGE, _TONE),
    "grunge_map_012": (Recipe(cells=2, octaves=8, roughness=0.62, detail="speckle", detail_cells=16,
                              detail_weight=0.25, gain=1.5, offset=-0.2), _GRUNGE, _TONE),
    "grunge_map_013": (Recipe(kind="value", cells=4, octaves=6, roughness=0.55, detail="edges", detail_cells=6,
                              detail_weight=0.4, warp=0.1, gain=1.3), _GRUNGE, _TONE),
    "grunge_map_014": (Recipe(cells=1, aspect=(6, 1), octaves=6, roughness=0.6, mode="ridged", gain=1.4),
                       _GRUNGE, _TONE),
    "grunge_map_015": (Recipe(kind="value", cells=1, octaves=9, roughness=0.7, detail="cells", detail_cells=20,
                              detail_weight=0.3, gain=1.8), _GRUNGE, _TONE),
})

for _name, (_recipe, _scale, _extra) in GRUNGE_RECIPES.items():
    globals()[f"noise_{_name}"] = make_recipe_generator(_name, _recipe, _extra)
    __all__.append(f"noise_{_name}")
