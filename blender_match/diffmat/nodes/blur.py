"""Declarations of the blur family: Blur, Directional Blur, Sharpen (see functional/blur.py)."""
from .. import functional as F
from .registry import register
from .spec import Input, NodeSpec, Param

register(NodeSpec(
    "blur", "atomic", F.blur,
    inputs=(Input("input1"),),
    params=(Param("intensity", 10.0, 0.0, 32.0,
                  doc="box half-width in pixels of a 256-pixel image"),),
    doc="Blur (atomic quick blur): a wrap-around box blur."))

register(NodeSpec(
    "dirmotionblur", "atomic", F.directional_blur,
    inputs=(Input("input1"),),
    params=(Param("intensity", 10.0, 0.0, 32.0,
                  doc="half-length of the blur in pixels of a 256-pixel image"),
            Param("mblurangle", 0.0, 0.0, 1.0, doc="direction in turns, clockwise from +u")),
    aliases=("directional_blur",),
    doc="Directional Blur: a wrap-around box blur along one direction."))

register(NodeSpec(
    "sharpen", "atomic", F.sharpen,
    inputs=(Input("input1"),),
    params=(Param("intensity", 1.0, 0.0, 10.0,
                  doc="x + intensity (x - mean of the 4 neighbours 1/256 image away)"),),
    doc="Sharpen: Laplacian sharpening, clamped to [0, 1]."))
