"""Declarations of the tile-layout pattern generators (see functional/pattern_tiles.py)."""
from .. import functional as F
from ..functional.pattern_tiles import MAX_TILES, TILE_BLENDINGS, TILE_PATTERNS, TILE_SAMPLER_PATTERNS
from .registry import register
from .spec import Input, NodeSpec, Param

GEN = ("size", "seed", "device", "dtype")
PATTERN_DOC = ", ".join(f"{i} {n}" for i, n in enumerate(TILE_PATTERNS))
SAMPLER_PATTERN_DOC = ", ".join(f"{i} {n}" for i, n in enumerate(TILE_SAMPLER_PATTERNS))
BLENDING_DOC = "how overlapping tiles combine: 0 Add, 2 Max, 3 Add Sub (1: Add)"


def _layout(pattern=8, scale=1.0):
    return (
        Param("x_amount", 10, 1, MAX_TILES, kind="int", doc="tiles across"),
        Param("y_amount", 10, 1, MAX_TILES, kind="int", doc="tiles down"),
        Param("pattern", pattern, kind="enum", choices=tuple(range(len(TILE_PATTERNS))), doc=PATTERN_DOC),
        Param("pattern_specific", 0.2, 0.0, 1.0, doc="shape-dependent control (Brick: bevel width)"),
        Param("scale", scale, 0.0, 2.0, doc="1 fills the cell"),
        Param("size_xy", (1.0, 1.0), 0.0, 2.0, size=2,
              doc="non-uniform size (Substance's 'Size'; renamed: 'size' is the output size)"),
        Param("interstice", (0.0, 0.0), 0.0, 1.0, size=2, doc="gap, fraction of the cell (x, y)"),
        Param("offset", 0.0, 0.0, 1.0, doc="row k shifted by k × offset cells"),
        Param("position_random", (0.0, 0.0), 0.0, 1.0, size=2, doc="jitter up to ± this many cells (x, y)"),
        Param("scale_random", 0.0, 0.0, 1.0),
        Param("rotation", 0.0, 0.0, 1.0, doc="turns"),
        Param("rotation_random", 0.0, 0.0, 1.0, doc="rotation ± this many turns at random"),
        Param("luminance_random", 0.0, 0.0, 1.0),
        Param("mask_random", 0.0, 0.0, 1.0, doc="fraction of tiles hidden"),
        Param("softness", 0.0, 0.0, 1.0, doc="edge softness, fraction of the half size"),
        Param("checker_mask", False, kind="bool", doc="hides every other tile"),
        Param("horizontal_mask", False, kind="bool", doc="hides every other column"),
        Param("vertical_mask", False, kind="bool", doc="hides every other row"),
        Param("invert_mask", False, kind="bool", doc="shows only what the masks (random mask included) hide"),
        Param("blending_mode", 0, kind="enum", choices=tuple(range(len(TILE_BLENDINGS))), doc=BLENDING_DOC),
        Param("global_opacity", 1.0, 0.0, 1.0, optimizable=False, doc="scales what the tiles add"),
        Param("luminance_by_number", False, kind="bool", doc="fades the tiles' luminance over their order"),
        Param("offset_random", 0.0, 0.0, 1.0, optimizable=False,
              doc="row k shifted at random by up to offset_random x (k + 1) / rows of the image"),
        Param("vertical_offset", False, kind="bool", doc="offsets columns (down) instead of rows"),
        Param("global_offset", (0.0, 0.0), -1.0, 1.0, size=2, optimizable=False,
              doc="moves the whole layout (x, y), fractions of the image"),
        Param("reverse_rendering_order", False, kind="bool",
              doc="the tiles take their random values in the reverse order"),
        Param("luminance_by_scale", False, kind="bool", doc="each tile's luminance times its random scale"),
        Param("offset_random_seed", 0, 0, 2 ** 31 - 1, kind="int", optimizable=False,
              doc="the older node's seed of its random row shifts (0: the layout's own)"),
        Param("scale_random_seed", 0, 0, 2 ** 31 - 1, kind="int", optimizable=False,
              doc="the older node's seed of its random scales (0: the layout's own)"))


register(NodeSpec(
    "tile_generator", "generator", F.tile_pattern,
    inputs=(Input("pattern_input_1", "any", optional=True),),
    params=_layout() + (Param("background_level", 0.0, 0.0, 1.0, optimizable=False, doc="the grey under the tiles"),),
    context=GEN,
    doc="Tile Generator: a grid of shapes with per-tile random variations."))

register(NodeSpec(
    "tile_generator_color", "generator", F.tile_pattern_color,
    inputs=(Input("pattern_input_1", "any", optional=True),),
    params=_layout() + (
        Param("color_random", 1.0, 0.0, 1.0, doc="mix of a random colour per tile"),
        Param("pattern_color", (1.0, 1.0, 1.0, 1.0), size=4, doc="RGBA"),
        Param("background_color", (0.0, 0.0, 0.0, 1.0), size=4, doc="RGBA")),
    context=GEN,
    doc="Tile Generator Color: the tile layout with a colour per tile (RGBA)."))

register(NodeSpec(
    "tile_sampler", "generator", F.tile_sampler_pattern,
    inputs=(Input("pattern_input", "any", optional=True),),
    params=(Param("x_amount", 16, 1, MAX_TILES, kind="int"),
            Param("y_amount", 16, 1, MAX_TILES, kind="int"),
            Param("pattern", 1, kind="enum", choices=tuple(range(len(TILE_SAMPLER_PATTERNS))),
                  doc=SAMPLER_PATTERN_DOC),
            Param("scale", 0.8, 0.0, 2.0),
            Param("size_xy", (1.0, 1.0), 0.0, 2.0, size=2, doc="non-uniform size"),
            Param("position_random", 0.0, 0.0, 1.0),
            Param("offset", 0.0, 0.0, 1.0),
            Param("rotation", 0.0, 0.0, 1.0),
            Param("rotation_random", 0.0, 0.0, 1.0),
            Param("scale_random", 0.0, 0.0, 1.0),
            Param("luminance_random", 0.0, 0.0, 1.0),
            Param("mask_random", 0.0, 0.0, 1.0)),
    context=GEN,
    doc="Tile Sampler (simplified): the tile layout with Tile Sampler's parameters."))

register(NodeSpec(
    "brick_generator", "generator", F.brick_pattern,
    params=(Param("x_amount", 4, 1, 256, kind="int"),
            Param("y_amount", 8, 1, 256, kind="int"),
            Param("offset", 0.5, 0.0, 1.0, doc="alternate rows shift, bricks"),
            Param("interstice", (0.04, 0.08), 0.0, 0.5, size=2, doc="gap, fraction of the brick (x, y)"),
            Param("bevel", 0.1, 0.0, 0.5, doc="fraction of the brick height"),
            Param("luminance_random", 0.3, 0.0, 1.0),
            Param("mask_random", 0.0, 0.0, 1.0),
            Param("height", F.pattern_tiles.FLAT_BRICKS, -1.0, 1.0, size=4, optimizable=False,
                  doc="(min, max, balance, variance): each brick at min or max, lowered at random"),
            Param("slope", F.pattern_tiles.NO_SLOPE, -1.0, 1.0, size=4, optimizable=False,
                  doc="(x, y, balance, variance): a ramp across each brick (brick_relief)")),
    context=GEN,
    doc="Brick Generator: offset rows of bevelled bricks."))

register(NodeSpec(
    "checker_1", "generator", F.checker_pattern,
    params=(Param("tiling", 2, 1, 64, kind="int", doc="checker periods per side (2·tiling squares)"),),
    context=("size", "device", "dtype"),
    doc="Checker 1: a checkerboard."))

register(NodeSpec(
    "parquet_1", "generator", F.parquet_pattern,
    params=(Param("tiling", 4, 1, 64, kind="int", doc="blocks per side"),
            Param("planks", 3, 1, 16, kind="int", doc="planks per block"),
            Param("gap", 0.02, 0.0, 0.2, doc="fraction of a block"),
            Param("bevel", 0.05, 0.0, 0.5, doc="fraction of a plank's width"),
            Param("luminance_random", 0.3, 0.0, 1.0)),
    context=GEN,
    doc="Parquet 1: basket-weave parquet planks."))

register(NodeSpec(
    "weave_generator", "generator", F.weave_pattern,
    params=(Param("tiling", 4, 1, 64, kind="int", doc="2·tiling threads each way"),
            Param("width", (0.8, 0.8), 0.0, 1.0, size=2, doc="thread width, fraction of the spacing (x, y)"),
            Param("luminance_random", 0.2, 0.0, 1.0)),
    context=GEN,
    doc="Weave Generator: interlaced threads."))

register(NodeSpec(
    "weave_1", "generator", F.plain_weave,
    params=(Param("tiling", 4, 1, 64, kind="int", doc="repeats of the two-thread weave each way"),),
    context=GEN,
    doc="Weave 1: a simple (plain) weave, threads of one shade."))

register(NodeSpec(
    "mesh_1", "generator", F.mesh_pattern,
    params=(Param("tiling", 4, 1, 64, kind="int", doc="2·tiling wires each way"),
            Param("width", 0.3, 0.0, 1.0, doc="wire width, fraction of the spacing")),
    context=GEN,
    doc="Mesh 1: a wire mesh."))

register(NodeSpec(
    "splatter_circular", "generator", F.circular_splatter,
    params=(Param("pattern", 2, kind="enum", choices=tuple(range(1, len(TILE_PATTERNS))), doc=PATTERN_DOC),
            Param("pattern_amount", 8, 1, 64, kind="int"),
            Param("radius", 0.3, 0.0, 0.5, doc="ring radius, image widths"),
            Param("pattern_size", 0.15, 0.0, 0.5, doc="copy width, image widths"),
            Param("pattern_specific", 0.5, 0.0, 1.0),
            Param("ring_rotation", 0.0, 0.0, 1.0, doc="turns"),
            Param("pattern_rotation", 0.0, 0.0, 1.0, doc="turns, relative to the ring"),
            Param("scale_random", 0.0, 0.0, 1.0),
            Param("luminance_random", 0.0, 0.0, 1.0)),
    context=GEN,
    doc="Splatter Circular: copies of a shape around a circle."))
