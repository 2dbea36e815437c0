"""Declarations of the library blur / warp / transform nodes (see functional/library_blur.py)."""
from .. import functional as F
from .registry import register
from .spec import Input, NodeSpec, Param

NA = "non_atomic"


def _gray_and_color(gray: str, color: str, fn, primary: str, doc: str, *, inputs=(), aliases=(), **spec):
    """Register a library node's grayscale and colour variants: one op, one parameter list, the
    primary input gray in the first and colour in the second (aliases go to the grayscale one)."""
    register(NodeSpec(gray, NA, fn, inputs=(Input(primary, "gray"), *inputs), aliases=aliases,
                      doc=f"{doc} (grayscale).", **spec))
    register(NodeSpec(color, NA, fn, inputs=(Input(primary, "color"), *inputs), doc=f"{doc} (colour).", **spec))

_BLUR_HQ = (Param("intensity", 10.0, 0.0, 16.0, doc="256-px pixels (sigma = intensity / 2)"),
            Param("quality", 0.0, optimizable=False, doc="sample quality (no effect: exact FFT blur)"))
_gray_and_color("blur_hq_grayscale", "blur_hq", F.blur_hq, "source", "Blur HQ: Gaussian blur",
                outputs=("blur_hq",), params=_BLUR_HQ)

register(NodeSpec(
    "highpass_grayscale", NA, F.highpass, inputs=(Input("source"),), outputs=("highpass",),
    params=(Param("radius", 6.0, 0.0, 64.0, doc="256-px pixels"),),
    doc="Highpass: detail above the radius, around mid-gray."))

_SLOPE = (Param("samples", 8, 1, 32, kind="int", doc="at most 4 are taken"),
          Param("mode", 1, kind="enum", choices=(0, 1, 5, 6, 7),
                doc="7 blur (Substance's code; 0 and 1 also blur), 5 max, 6 min"),
          Param("intensity", 10.0, -16.0, 16.0, doc="256-px pixels along the slope"))
_gray_and_color("slope_blur_grayscale", "slope_blur", F.slope_blur, "source",
                "Slope Blur: smear along the slope of a height map", inputs=(Input("effect", "gray"),),
                aliases=("slope_blur_grayscale_2",), outputs=("slope_blur",), params=_SLOPE)

register(NodeSpec(
    "non_uniform_blur_grayscale", NA, F.non_uniform_blur,
    inputs=(Input("source", "gray"), Input("effect", "gray")), outputs=("non_uniform_blur",),
    params=(Param("intensity", 10.0, 0.0, 16.0, doc="256-px pixels where effect is white"),
            Param("anisotropy", 0.0), Param("asymmetry", 0.0), Param("angle", 0.0, doc="turns"),
            Param("samples", 4, 1, 16, kind="int", doc="blur levels (at most 6)"),
            Param("blades", 5, 1, 9, kind="int", doc="bokeh blades (not modelled)")),
    aliases=("non_uniform_blur",),
    doc="Non-Uniform Blur: blur radius driven by an effect map."))

_gray_and_color("vector_warp_grayscale", "vector_warp", F.vector_warp, "input",
                "Vector Warp: displacement by an RG vector map", inputs=(Input("vector_map", "color"),),
                params=(Param("intensity", 1.0, 0.0, 1.0, doc="image widths per unit vector"),
                        Param("vector_format", 0, kind="enum", choices=(0, 1), doc="0 DirectX, 1 OpenGL")))

register(NodeSpec(
    "vector_morph_grayscale", NA, F.vector_morph,
    inputs=(Input("input", "gray"), Input("vector_field", "color")),
    params=(Param("amount", 1.0, 0.0, 1.0, doc="path length: amount x 0.25 image widths"),
            Param("vector_format", 0, kind="enum", choices=(0, 1), doc="0 DirectX, 1 OpenGL")),
    doc="Vector Morph: advection along a vector field."))

register(NodeSpec(
    "mosaic_grayscale", NA, F.mosaic,
    inputs=(Input("input", "gray"), Input("effect", "gray", optional=True)),
    params=(Param("intensity", 0.5), Param("samples", 4, 1, 16, kind="int", doc="warp steps (at most 4)")),
    doc="Mosaic: multi-step self/effect-driven warp."))

_SAFE = (Param("tile", 1, 1, 64, kind="int"),
         Param("tile_mode", 0, kind="enum", choices=(0, 1), doc="0 uniform tile, 1 tile_xy"),
         Param("tile_xy", (1.0, 1.0), 1.0, 64.0, size=2, optimizable=False),
         Param("tile_safe_rotation", True, kind="bool"),
         Param("offset", (0.0, 0.0), -1.0, 1.0, size=2),
         Param("offset_mode", 0, kind="enum", choices=(0, 1), doc="0 manual, 1 random"),
         Param("rotation", 0.0, 0.0, 1.0, doc="turns"),
         Param("symmetry", 0, kind="enum", choices=(0, 1, 2, 3), doc="none, X, Y, X+Y"),
         Param("mipmap_mode", 0, kind="enum", choices=(0, 1)),
         Param("mipmap_level", 0, 0, 12, kind="int"))
_gray_and_color("safe_transform_grayscale", "safe_transform", F.safe_transform, "input", "Safe Transform",
                params=_SAFE, context=("seed",))

_PATCH = (Param("octave", 3, 0, 8, kind="int", doc="2^octave cells per side"),
          Param("mask_size", 1.0, doc="reach of the stamps' round mask"),
          Param("mask_precision", 0.5, doc="hardness of the mask's edge"),
          Param("mask_warping", 0.0, -100.0, 100.0, doc="the mask's edge bent along the input's slope"),
          Param("pattern_size_width", 200.0, 0.0, 1000.0, doc="stamp width, percent of a cell"),
          Param("pattern_size_height", 200.0, 0.0, 1000.0, doc="stamp height, percent of a cell"),
          Param("disorder", 0.0, doc="random move of each stamp, image widths"),
          Param("size_variation", 0.0, 0.0, 100.0, doc="random size change, percent of a cell"),
          Param("rotation", 0.0, -1.0, 1.0, doc="turns"),
          Param("rotation_variation", 0.0, doc="random extra turn, up to this many turns"),
          Param("color_variation", 0.0, doc="random darkening of each stamp (grayscale: Luminosity Variation)"),
          Param("background_color", (0.0, 0.0, 0.0, 1.0), size=4, doc="where no stamp reaches (colour node)"))
_gray_and_color("make_it_tile_patch_grayscale", "make_it_tile_patch", F.make_it_tile_patch, "source",
                "Make It Tile Patch", outputs=("make_it_tile_patch",), params=_PATCH, context=("seed",))

_PHOTO = tuple(p for axis in ("h", "v") for p in (
    Param(f"mask_warping_{axis}", 0.0, -100.0, 100.0, doc="the fade bent along the blurred image"),
    Param(f"mask_size_{axis}", 0.5, doc="how far the fade reaches"),
    Param(f"mask_precision_{axis}", 0.5, doc="hardness of the fade")))
_gray_and_color("make_it_tile_photo_grayscale", "make_it_tile_photo", F.make_it_tile_photo, "source",
                "Make It Tile Photo", outputs=("make_it_tile_photo",), params=_PHOTO)
