"""Declarations of Normal and Emboss (see functional/relief.py)."""
from .. import functional as F
from .registry import register
from .spec import Input, NodeSpec, Param

register(NodeSpec(
    "normal", "atomic", F.height_to_normal,
    inputs=(Input("input1", "gray"),),
    params=(
        Param("intensity", 1.0, 0.0, 100.0, doc="height scale (per pixel of a 256-pixel image)"),
        Param("inversedy", False, kind="bool", doc="normal format: False DirectX, True OpenGL"),
        Param("input2alpha", True, kind="bool", doc="copy the height into alpha (else alpha is 1)"),
    ),
    doc="Normal: converts a height map to a tangent-space normal map."))

register(NodeSpec(
    "emboss", "atomic", F.emboss,
    inputs=(Input("input1"), Input("inputgradient", "gray")),
    params=(
        Param("intensity", 5.0, 0.0, 50.0, doc="relief strength (per pixel of a 256-pixel image)"),
        Param("lightangle", 0.0, 0.0, 1.0, doc="light direction in turns (0 from the right, 0.25 from the top)"),
        Param("highlightcolor", (1.0, 1.0, 1.0, 1.0), size=4, doc="colour of the lit slopes"),
        Param("shadowcolor", (0.0, 0.0, 0.0, 0.0), size=4, doc="colour of the slopes in shadow"),
    ),
    doc="Emboss: lights input1 as if raised by the height inputgradient."))
