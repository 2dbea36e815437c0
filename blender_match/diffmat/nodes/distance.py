"""Declaration of the Distance node (see functional/distance.py)."""
from .. import functional as F
from .registry import register
from .spec import Input, NodeSpec, Param

register(NodeSpec(
    "distance", "atomic", F.distance,
    inputs=(Input("mask", "gray"), Input("source", "any", optional=True)),
    params=(Param("distance", 10.0, 0.0, 256.0, doc="maximum distance in pixels of a 256-pixel image"),
            Param("colorswitch", False, kind="bool", doc="colour (True) or grayscale output"),
            Param("combinedistance", True, kind="bool",
                  doc="multiply the source value by the distance fade")),
    doc="Distance: a wrap-around linear fade from the mask, or the source's value at the nearest mask pixel."))
