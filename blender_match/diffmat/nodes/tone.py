"""Declarations of the tone and channel nodes: Levels, Curve, HSL, Grayscale Conversion and
Channel Shuffle (see functional/tone.py)."""
from .. import functional as F
from .registry import register
from .spec import Input, NodeSpec, Param

register(NodeSpec(
    "levels", "atomic", F.levels,
    inputs=(Input("input1"),),
    params=(
        Param("levelinlow", (0.0, 0.0, 0.0, 0.0), size=4, doc="input black point per RGBA"),
        Param("levelinmid", (0.5, 0.5, 0.5, 0.5), size=4,
              doc="mid point per RGBA: exponent 1 + 8 |2 mid - 1| (at most 9), inverted below 0.5"),
        Param("levelinhigh", (1.0, 1.0, 1.0, 1.0), size=4, doc="input white point per RGBA"),
        Param("leveloutlow", (0.0, 0.0, 0.0, 0.0), size=4, doc="output level for the input black point"),
        Param("levelouthigh", (1.0, 1.0, 1.0, 1.0), size=4, doc="output level for the input white point"),
        Param("clampinterm", True, kind="bool", doc="clamp the normalised input to [0, 1] before the gamma"),
    ),
    doc="Levels: remaps each channel's input range, mid-point gamma and output range."))

register(NodeSpec(
    "curve", "atomic", F.curve,
    inputs=(Input("input1"),),
    params=(
        Param("positions", (0.0, 0.0, 1.0, 1.0), size=None, doc="curve points, (x, y) pairs"),
        Param("lefts", (0.0, 0.0, 2 / 3, 2 / 3), size=None, doc="left Bézier handles, (x, y) per point"),
        Param("rights", (1 / 3, 1 / 3, 1.0, 1.0), size=None, doc="right Bézier handles, (x, y) per point"),
    ),
    doc="Curve: a luminance curve (cubic Bézier through points with handles) applied to RGB or gray. "
        "Translated from the curveluminance paramsArray (position/left/right of each cell)."))

register(NodeSpec(
    "hsl", "atomic", F.hsl,
    inputs=(Input("input1", "color"),),
    params=(
        Param("hue", 0.5, doc="hue shift of (2 hue - 1) turns: 0, 0.5 and 1 leave the hue unchanged"),
        Param("saturation", 0.5, doc="adds 2 saturation - 1 to the saturation (0.5 unchanged, 0 gray)"),
        Param("luminosity", 0.5, doc="adds 2 luminosity - 1 to the lightness (0.5 unchanged, 0 black, 1 white)"),
    ),
    doc="HSL: adjusts hue, saturation and lightness of a colour image."))

register(NodeSpec(
    "grayscaleconversion", "atomic", F.grayscale_conversion,
    inputs=(Input("input1", "color"),),
    params=(
        Param("channelsweights", (0.33, 0.33, 0.33, 0.0), size=4, doc="weights of R, G, B, A"),
        Param("alphamult", False, kind="bool", doc="flatten alpha over a background of mattelevel"),
        Param("mattelevel", 1.0, doc="background gray level used when flattening alpha"),
    ),
    doc="Grayscale Conversion: a weighted sum of the RGBA channels."))

register(NodeSpec(
    "shuffle", "atomic", F.channel_shuffle,
    inputs=(Input("input1"), Input("input2", optional=True)),
    params=tuple(Param(name, default, kind="enum", choices=tuple(range(8)),
                       doc="0-3 input1 R, G, B, A; 4-7 input2 R, G, B, A")
                 for name, default in (("channelred", 0), ("channelgreen", 1), ("channelblue", 2),
                                       ("channelalpha", 3))),
    doc="Channel Shuffle: builds an RGBA image from channels of one or two inputs."))
