"""Identifier aliases: where a real .sbs file names a parameter or an input differently from the
node spec (whose names are Substance's current identifiers in lower case).

Real production files were saved with many versions of the Substance library: a graph keeps its
name across versions while some of its parameter identifiers change (``tile_generator``'s
``pattern_size`` / ``position_offset`` / ``random_mask``, ``shape``'s ``Size``, the legacy noises'
``Distance``), and identifiers come in any case and with dashes or spaces. Resolution of a file
identifier against a spec, first match wins:

1. the identifier normalised (lower case, runs of characters other than ``a-z0-9`` become ``_``);
2. ``PARAM_ALIASES[node]`` / ``INPUT_ALIASES[node]`` (the documented table below; a parameter alias
   may name several spec parameters, one per component of the file's vector value);
3. the same with every ``_`` removed on both sides (``input1`` = ``input_1``, ``levelinlow`` =
   ``level_in_low``);
4. the identifier without a leading word of the node's own name (``scratches_amount`` on
   ``scratches_generator`` -> ``amount``).

Value conversions (``convert_value``) for parameters whose meaning differs between library
versions: a legacy ``Disorder`` slider runs 0..100 where the specs' ``disorder`` is 0..1 (a value
above 1 is divided by 100); ``gradient_linear_*``'s ``rotation`` is an integer index of quarter
turns in the library and turns in the specs; Make It Tile Patch's angles are degrees; the
Scratches Generator's ``Spline Number`` (and the older ``Scratches Amount``) counts every scratch,
where our ``amount`` is the side of a lattice holding two a cell.
"""
from __future__ import annotations

import math
import re

# node (spec name) -> {normalised file identifier: spec parameter, or a tuple of spec parameters
# taking the file value's components in order}
# the tile layouts' identifiers that Tile Sampler and the Tile Generators share
TILE_LAYOUT_ALIASES: dict[str, str | tuple[str, ...]] = {
    "pattern_size": "size_xy", "size": "size_xy", "position_offset": "offset",
    "random_mask": "mask_random", "nb_x": "x_amount", "nb_y": "y_amount",
    "luminance_variation": "luminance_random",
}
TILE_GENERATOR_ALIASES: dict[str, str | tuple[str, ...]] = {
    **TILE_LAYOUT_ALIASES, "pattern_type": "pattern", "luminance_variation_contrast": "luminance_random",
    "pattern_size_random": "scale_random", "randommask": "mask_random", "position_offset_random": "offset_random",
    # the older Tile Generator's: free rotation and its random spread in degrees (``convert_value``)
    "free_rotation": "rotation", "free_rotation_random": "rotation_random", "scalevariation": "scale_random",
    "scalevariation_seed": "scale_random_seed",
    "luminancebyscalevariation": "luminance_by_scale",
}
# the current Scratches Generator's "Spline" identifiers (its documentation; the Normal version
# shares them): a count of all the scratches (converted to our cells a side, ``convert_value``), a
# rotation and its random spread in turns, a random length spread; Spline Scale and Width have
# units we do not know
SCRATCHES = ("scratches_generator", "scratches_generator_normal")
# the identifiers that count every scratch: the current Spline Number (1-512, "amount of scratches",
# its documentation) and the older Scratches Amount (production files set 30 and 3965)
SCRATCH_COUNTS = ("spline_number", "scratches_amount")
SCRATCHES_ALIASES: dict[str, str | tuple[str, ...]] = {
    "scratches_amount": "amount", "spline_number": "amount", "spline_rotation": "angle",
    "spline_rotation_random": "angle_random", "spline_scale_random": "length_random",
}
PARAM_ALIASES: dict[str, dict[str, str | tuple[str, ...]]] = {
    # pattern generators: library identifiers (current and older library versions)
    "tile_generator": {**TILE_GENERATOR_ALIASES, "background_color": "background_level"},
    "tile_generator_color": {**TILE_GENERATOR_ALIASES, "color_variation": "color_random", "color": "pattern_color"},
    "tile_sampler": TILE_LAYOUT_ALIASES,
    "shape": {"size": "scale", "rotation": "rotation_45", "variation": "pattern_specific"},
    "brick_generator": {"bricks": ("x_amount", "y_amount"), "gap": "interstice"},
    "parquet_1": {"luminance_variation": "luminance_random"},
    **{name: SCRATCHES_ALIASES for name in SCRATCHES},
    "mesh_1": {"mesh_width": "width"},
    "stripes": {"stripes": "number"},
    # the older Anisotropic Noise's name of its Y Amount By Resolution switch
    "anisotropic_noise": {"y_by_resolution": "y_amount_by_resolution"},
    # legacy noises: "Distance" is the zoom / scale slider (cells: 10-30 in production files)
    "perlin_noise_zoom": {"distance": "scale"},
    "plasma": {"distance": "scale"},
    **{f"cells_{k}": {"distance": "scale"} for k in range(1, 5)},
    # filters
    "normal_to_height": {"global_opacity": "opacity"},
    "non_uniform_blur_grayscale": {"blade": "blades"},
    "make_it_tile_patch_grayscale": {"octaves": "octave", "luminosity_variation": "color_variation"},
    "make_it_tile_patch": {"octaves": "octave"},
}

# node -> {normalised file input identifier: spec input slot}
INPUT_ALIASES: dict[str, dict[str, str]] = {
    "normal_blend": {"normal_bg": "normalbg", "normal_fg": "normalfg", "background": "normalbg",
                     "foreground": "normalfg"},
    "vector_warp": {"vector": "vector_map", "vectormap": "vector_map"},
    "vector_warp_grayscale": {"vector": "vector_map", "vectormap": "vector_map"},
    "slope_blur_grayscale": {"input": "source", "slope": "effect"},
    "slope_blur": {"input": "source", "slope": "effect"},
    "non_uniform_blur_grayscale": {"input": "source", "blur_map": "effect"},
    # Mosaic's current identifiers are Source and Effect
    "mosaic_grayscale": {"source": "input"},
}

# parameters whose file value is rescaled: (node or "*", spec parameter) -> converter
QUARTER_TURN_ROTATION = {"gradient_linear_1", "gradient_linear_2", "gradient_linear_3"}
# angles that the library's sliders give in degrees and the specs in turns (Make It Tile Patch:
# Rotation -360..360, Rotation Variation 0..360, its documentation)
DEGREE_ANGLES = {(node, param) for node in ("make_it_tile_patch", "make_it_tile_patch_grayscale")
                 for param in ("rotation", "rotation_variation")}


def norm(identifier: str) -> str:
    """A file identifier in the specs' form: lower case, ``[^a-z0-9]`` runs as ``_``."""
    return re.sub(r"[^a-z0-9]+", "_", str(identifier).lower()).strip("_")


def _squash(text: str) -> str:
    return text.replace("_", "")


def resolve_param(spec, identifier: str) -> list[tuple[str, int | None]]:
    """The spec parameters that a file parameter ``identifier`` sets: a list of (name, component
    of the file value or None for the whole value); empty when none matches."""
    index = spec.param_index
    low = str(identifier).lower()
    if low in index:
        return [(low, None)]
    key = norm(identifier)
    if key in index:
        return [(key, None)]
    alias = PARAM_ALIASES.get(spec.name, {}).get(key)
    if alias is not None:
        if isinstance(alias, tuple):
            return [(a, i) for i, a in enumerate(alias) if a in index]
        if alias in index:
            return [(alias, None)]
    squashed = {_squash(name): name for name in index}
    if _squash(key) in squashed:
        return [(squashed[_squash(key)], None)]
    words = set(spec.name.split("_"))
    head, _, rest = key.partition("_")
    if rest and head in words:
        if rest in index:
            return [(rest, None)]
        if _squash(rest) in squashed:
            return [(squashed[_squash(rest)], None)]
    return []


def resolve_input(spec, identifier: str) -> str | None:
    """The spec input slot for a file connection ``identifier`` (None when none matches)."""
    names = [s.name for s in spec.inputs]
    low = str(identifier).lower().replace(":", "_")
    if low in names:
        return low
    key = norm(identifier)
    if key in names:
        return key
    alias = INPUT_ALIASES.get(spec.name, {}).get(key)
    if alias in names:
        return alias
    squashed = {_squash(n): n for n in names}
    return squashed.get(_squash(key))


def convert_value(spec_name: str, param: str, identifier: str, value):
    """A file value rescaled where the library's meaning differs from the spec's (see module doc).
    ``value`` is a number, a list or a bool; returned unchanged when no rule applies."""
    if isinstance(value, bool) or isinstance(value, str):
        return value
    if param == "disorder" and isinstance(value, (int, float)) and value > 1.0:
        return value / 100.0
    if param == "rotation" and spec_name in QUARTER_TURN_ROTATION and isinstance(value, int):
        return (value % 4) * 0.25
    if (spec_name, param) in DEGREE_ANGLES and isinstance(value, (int, float)):
        return value / 360.0
    ident = norm(identifier)
    if ident == "free_rotation" and isinstance(value, (int, float)):
        return (value / 360.0) % 1.0
    if ident == "free_rotation_random" and isinstance(value, (int, float)):
        return min(value / 720.0, 0.5)   # a spread of that many degrees in all, ± half of it: 360 is any angle
    if spec_name in SCRATCHES and ident in SCRATCH_COUNTS and isinstance(value, (int, float)):
        return max(1, round(math.sqrt(value / 2.0)))   # two scratches a cell of an amount x amount lattice
    return value


__all__ = ["PARAM_ALIASES", "INPUT_ALIASES", "norm", "resolve_param", "resolve_input", "convert_value"]
