"""Declarations of the input nodes Bitmap, SVG and Text (see functional/inputs.py)."""
from .. import functional as F
from .registry import register
from .spec import Input, NodeSpec, Param

CONTEXT = ("size", "device", "dtype")

register(NodeSpec(
    "bitmap", "atomic", F.bitmap,
    params=(
        Param("bitmapresourcepath", "", kind="string", doc="path of the image file ('' = unset: black)"),
        Param("colorswitch", True, kind="bool", doc="colour (True) or grayscale output"),
    ),
    context=CONTEXT,
    doc="Bitmap: an image file resized (wrap-around) to the graph's size."))

register(NodeSpec(
    "svg", "atomic", F.svg,
    inputs=(Input("background", optional=True),),
    params=(
        Param("vectorresourcepath", "", kind="string", doc="SVG resource (ignored: placeholder)"),
        Param("background", (0.0, 0.0, 0.0, 0.0), size=4, doc="background colour"),
        Param("colorswitch", True, kind="bool", doc="colour (True) or grayscale output"),
    ),
    context=CONTEXT,
    doc="SVG placeholder: renders its background (image input or colour); vector drawing is not rasterised."))

register(NodeSpec(
    "text", "atomic", F.text,
    inputs=(Input("background", optional=True),),
    params=(
        Param("text", "", kind="string", doc="the text (ignored: placeholder)"),
        Param("fontdata", "", kind="string", doc="font family|style (ignored)"),
        Param("fontsize", 0.25, optimizable=False, doc="font size (ignored)"),
        Param("frontcolor", (1.0, 1.0, 1.0, 1.0), size=4, optimizable=False, doc="text colour (ignored)"),
        Param("position", (0.5, 0.5), size=2, optimizable=False, doc="text position (ignored)"),
        Param("alignment", 1, kind="enum", choices=(0, 1, 2), doc="0 left, 1 center, 2 right (ignored)"),
        Param("matrix22", (1.0, 0.0, 0.0, 1.0), -2.0, 2.0, size=4, optimizable=False, doc="text transform (ignored)"),
        Param("background", (0.0, 0.0, 0.0, 0.0), size=4, doc="background colour"),
        Param("colorswitch", True, kind="bool", doc="colour (True) or grayscale output"),
    ),
    context=CONTEXT,
    doc="Text placeholder: renders its background (image input or colour); no font rasteriser."))
