"""Declaration of the FX-Map node in the MATch paper's tiling form (see functional/fxmap.py)."""
from .. import functional as F
from .registry import register
from .spec import Input, NodeSpec, Param

register(NodeSpec(
    "fxmaps", "atomic", F.fx_map,
    inputs=(Input("inputpattern", "any"), Input("background", "any", optional=True)),
    params=(Param("x_amount", 4, 1, 256, kind="int", doc="cells per row"),
            Param("y_amount", 4, 1, 256, kind="int", doc="rows"),
            Param("offset", 0.0, 0.0, 1.0, doc="shift of every other row, in cells"),
            Param("scale", 1.0, 0.0, 2.0, doc="copy size, in cells"),
            Param("rotation", 0.0, 0.0, 1.0, doc="copy rotation, turns"),
            Param("position_random", 0.0, 0.0, 1.0, doc="position jitter, in cells"),
            Param("rotation_random", 0.0, 0.0, 1.0, doc="rotation jitter, turns"),
            Param("scale_random", 0.0, 0.0, 1.0, doc="relative scale jitter"),
            Param("opacity_random", 0.0, 0.0, 1.0, doc="opacity jitter"),
            Param("opacitymult", 1.0, 0.0, 1.0, doc="opacity of every copy"),
            Param("blendingmode", 0, kind="enum", choices=(0, 1, 2), doc="0 add, 1 max, 2 alpha-blend"),
            Param("background", (0.0, 0.0, 0.0, 1.0), size=4, doc="background colour (RGBA)"),
            Param("colorswitch", False, kind="bool", doc="colour (True) or grayscale output")),
    context=("size", "seed", "device", "dtype"),
    aliases=("fx_map",),
    doc="FX-Map (tiling form): one pattern tiled in a grid with seeded jitter, over a background."))
