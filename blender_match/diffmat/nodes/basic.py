"""Declarations of the simplest nodes (see functional/basic.py)."""
from .. import functional as F
from ..functional.basic import METALS
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

register(NodeSpec(
    "pbr_metal_reflectance", "non_atomic", F.metal_reflectance,
    params=(Param("metal_color", 0, kind="enum", choices=tuple(range(len(METALS))),
                  doc=", ".join(f"{i} {m}" for i, m in enumerate(METALS))),),
    context=("size", "device", "dtype"),
    doc="PBR Metal Reflectance: the base colour of a pure metal."))
