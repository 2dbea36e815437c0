"""Declaration of the Blend node (see functional/blend.py)."""
from .. import functional as F
from ..functional.blend import BLEND_MODES
from .registry import register
from .spec import Input, NodeSpec, Param

register(NodeSpec(
    "blend", "atomic", F.blend,
    inputs=(Input("source"), Input("destination"), Input("opacity", "gray", optional=True)),
    params=(
        Param("blendingmode", 0, kind="enum", choices=tuple(BLEND_MODES),
              doc="0 copy, 1 add, 2 subtract, 3 multiply, 4 add-sub, 5 max, 6 min, 7 switch, 8 divide, "
                  "9 overlay, 10 screen, 11 soft light"),
        Param("opacitymult", 1.0, doc="opacity, clamped to [0, 1]; multiplies the opacity mask"),
        Param("alphablending", 0, kind="enum", choices=(0, 1, 2, 3),
              doc="0 use source alpha, 1 ignore alpha, 2 straight, 3 premultiplied"),
        Param("maskrectangle", (0.0, 1.0, 0.0, 1.0), size=4, optimizable=False,
              doc="cropping area left right top bottom (texture units); outside it only the background "
                  "shows. Not optimised: materials rarely crop a blend, and four values per blend would "
                  "crowd the parameter vector"),
    ),
    doc="Blend: composites the foreground (source) over the background (destination, primary) with a "
        "blending mode, an opacity and an optional grayscale opacity mask."))
