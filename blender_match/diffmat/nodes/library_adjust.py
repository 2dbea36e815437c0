"""Declarations of the library adjustment nodes (see functional/library_adjust.py)."""
from .. import functional as F
from .registry import register
from .spec import Input, NodeSpec, Param

NA = "non_atomic"
GRAY_COLOR = (0.5, 0.5, 0.5, 1.0)

register(NodeSpec(
    "histogram_scan", NA, F.histogram_scan,
    inputs=(Input("input_1"),),
    params=(Param("position", 0.0, doc="window position: 0 black, 1 white"),
            Param("contrast", 0.0, doc="0 one-unit-wide window, 1 hard threshold"),
            Param("invert_position", False, kind="bool")),
    doc="Histogram Scan: threshold-like levels window scanning the histogram."))

register(NodeSpec(
    "histogram_range", NA, F.histogram_range,
    inputs=(Input("input"),),
    params=(Param("range", 0.5, doc="output range width"),
            Param("position", 0.5, doc="output range centre")),
    doc="Histogram Range: compresses the value range around a position."))

register(NodeSpec(
    "histogram_select", NA, F.histogram_select,
    inputs=(Input("input"),),
    params=(Param("position", 0.5), Param("range", 0.25), Param("contrast", 0.0)),
    doc="Histogram Select: isolates a band of values."))

register(NodeSpec(
    "invert_grayscale", NA, F.invert,
    inputs=(Input("source", "gray"),), outputs=("invert_grayscale",),
    params=(Param("invert", True, kind="bool"),),
    doc="Invert Grayscale: 1 - x."))

register(NodeSpec(
    "invert", NA, F.invert,
    inputs=(Input("source", "color"),), outputs=("invert_color",),
    params=(Param("invert", True, kind="bool"),),
    doc="Invert (colour): 1 - RGB, alpha kept."))

register(NodeSpec(
    "auto_levels", NA, F.auto_levels,
    inputs=(Input("input"),),
    params=(Param("quality", 0.0, optimizable=False, doc="histogram precision (no effect here)"),),
    doc="Auto Levels: stretch the value range to [0, 1]."))

_CL = (Param("contrast", 0.0, -1.0, 1.0), Param("luminosity", 0.0, -1.0, 1.0))
register(NodeSpec(
    "contrast_luminosity", NA, F.contrast_luminosity,
    inputs=(Input("input", "color"),), params=_CL,
    doc="Contrast/Luminosity (colour)."))
register(NodeSpec(
    "contrast_luminosity_grayscale", NA, F.contrast_luminosity,
    inputs=(Input("input", "gray"),), params=_CL,
    doc="Contrast/Luminosity (grayscale)."))

register(NodeSpec(
    "replace_color", NA, F.replace_color,
    inputs=(Input("input", "color"),),
    params=(Param("sourcecolor", GRAY_COLOR, size=4), Param("targetcolor", GRAY_COLOR, size=4)),
    doc="Replace Color: HSL shift taking sourcecolor to targetcolor."))

register(NodeSpec(
    "switch_grayscale", NA, F.switch,
    inputs=(Input("input_1", "gray"), Input("input_2", "gray")),
    params=(Param("switch", True, kind="bool", doc="True: input_1, False: input_2"),),
    doc="Switch (grayscale)."))
register(NodeSpec(
    "switch", NA, F.switch,
    inputs=(Input("input_1", "color"), Input("input_2", "color")),
    params=(Param("switch", True, kind="bool", doc="True: input_1, False: input_2"),),
    doc="Switch (colour)."))

_MS_INPUTS = 10
for _name, _ch in (("multi_switch_grayscale", "gray"), ("multi_switch", "color")):
    register(NodeSpec(
        _name, NA, F.multi_switch,
        inputs=tuple(Input(f"input_{i}", _ch, optional=i > 2) for i in range(1, _MS_INPUTS + 1)),
        params=(Param("input_number", 2, 2, _MS_INPUTS, kind="int"),
                Param("input_selection", 1, 1, _MS_INPUTS, kind="int")),
        doc="Multi Switch: one of up to ten inputs."))

register(NodeSpec(
    "rgba_merge", NA, F.rgba_merge,
    inputs=(Input("r", "gray"), Input("g", "gray"), Input("b", "gray"), Input("a", "gray", optional=True)),
    outputs=("rgba_merge",),
    params=(Param("usealpha", True, kind="bool"),),
    doc="RGBA Merge: four grayscale channels to RGBA."))
register(NodeSpec(
    "rgba_split", NA, F.rgba_split,
    inputs=(Input("rgba", "color"),), outputs=("r", "g", "b", "a"),
    doc="RGBA Split: RGBA to four grayscale channels."))
register(NodeSpec(
    "rgb-a_merge", NA, F.rgb_a_merge,
    inputs=(Input("rgb", "color"), Input("a", "gray")), outputs=("rgb-a_merge",),
    doc="RGB-A Merge: RGB of one image, alpha from a grayscale one."))
register(NodeSpec(
    "rgb-a_split", NA, F.rgb_a_split,
    inputs=(Input("rgba", "color"),), outputs=("rgb", "a"),
    doc="RGB-A Split: the RGB part (alpha 1) and the alpha."))

register(NodeSpec(
    "convert_to_srgb", NA, F.linear_to_srgb,
    inputs=(Input("input"),),
    doc="Convert to sRGB: linear to sRGB transfer curve."))
