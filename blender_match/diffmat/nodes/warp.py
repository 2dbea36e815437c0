"""Declarations of the warp family: Warp and Directional Warp (see functional/warp.py)."""
from .. import functional as F
from .registry import register
from .spec import Input, NodeSpec, Param

register(NodeSpec(
    "warp", "atomic", F.warp,
    inputs=(Input("input1"), Input("inputgradient", "gray")),
    params=(Param("intensity", 1.0, 0.0, 20.0,
                  doc="displacement in 256-px pixels per unit of slope (value per image width)"),),
    doc="Warp: displaces the input along the slope of the gradient input."))

register(NodeSpec(
    "directionalwarp", "atomic", F.directional_warp,
    inputs=(Input("input1"), Input("inputintensity", "gray")),
    params=(Param("intensity", 10.0, 0.0, 64.0,
                  doc="displacement in 256-px pixels where the intensity map is 1"),
            Param("warpangle", 0.0, 0.0, 1.0, doc="direction in turns, clockwise from +u")),
    aliases=("directional_warp",),
    doc="Directional Warp: displaces the input in one direction, scaled by an intensity map."))
