"""Declarations of Gradient Map and Gradient Dynamic (see functional/gradient_map.py)."""
from .. import functional as F
from ..functional.gradient_map import INTERP_MODES
from .registry import register
from .spec import Input, NodeSpec, Param

register(NodeSpec(
    "gradient", "atomic", F.gradient_map,
    inputs=(Input("input1", "gray"),),
    params=(
        Param("positions", (0.0, 1.0), size=None, doc="key positions (one per key; any order)"),
        Param("colors", (0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 1.0), size=None, doc="key colours, RGBA per key"),
        Param("interpmode", 0, kind="enum", choices=tuple(INTERP_MODES),
              doc="0 linear, 1 smooth, 2 flat tangents, 3 none"),
        Param("colorswitch", True, kind="bool", doc="colour (True) or grayscale output"),
        Param("addressingrepeat", False, kind="bool", doc="wrap the gradient around instead of clamping"),
    ),
    doc="Gradient Map: maps a grayscale image through a gradient of keys. Translated from the "
        "gradientrgba paramsArray (position/value of each cell)."))

register(NodeSpec(
    "dyngradient", "atomic", F.dynamic_gradient,
    inputs=(Input("input1", "gray"), Input("input2")),
    params=(
        Param("uvselector", 0, kind="enum", choices=(0, 1), doc="0 horizontal (read a row), 1 vertical (a column)"),
        Param("coordinate", 0.0, doc="the row (v) or column (u) of input2 to read, texture units"),
        Param("addressingrepeat", False, kind="bool", doc="wrap the lookup around input2 instead of clamping"),
    ),
    doc="Gradient Dynamic: maps a grayscale image through a gradient read from a row or column of input2."))
