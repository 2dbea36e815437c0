"""Declarations of the simplest atomic nodes (see functional/basic.py)."""
from .. import functional as F
from .registry import register
from .spec import Input, NodeSpec, Param

register(NodeSpec(
    "uniform", "atomic", F.uniform_color,
    params=(Param("outputcolor", (0.0, 0.0, 0.0, 1.0), size=4, doc="RGBA colour"),
            Param("colorswitch", True, kind="bool", doc="colour (True) or grayscale output")),
    context=("size", "device", "dtype"),
    doc="Uniform Color: a flat colour or gray level."))

register(NodeSpec(
    "passthrough", "atomic", F.passthrough,
    inputs=(Input("input"),),
    doc="Dot node: passes its input through unchanged."))
