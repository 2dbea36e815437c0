"""Declaration of Transformation 2D (see functional/transform.py)."""
from .. import functional as F
from .registry import register
from .spec import Input, NodeSpec, Param

register(NodeSpec(
    "transformation", "atomic", F.transformation_2d,
    inputs=(Input("input1"),),
    params=(Param("matrix22", (1.0, 0.0, 0.0, 1.0), -4.0, 4.0, size=4, optimizable=False,
                  doc="output-to-input matrix (a b c d, row-major); fixed: only integer matrices tile"),
            Param("offset", (0.0, 0.0), -1.0, 1.0, size=2, doc="translation in image widths"),
            Param("filtering", 0, kind="enum", choices=(0, 1), doc="0 bilinear, 1 nearest"),
            Param("mipmapmode", 0, kind="enum", choices=(0, 1), doc="0 automatic, 1 manual level"),
            Param("manualmiplevel", 0, 0, 16, kind="int", doc="mip level when mipmapmode is 1"),
            Param("mattecolor", (0.0, 0.0, 0.0, 1.0), size=4, optimizable=False,
                  doc="unused: tiling is always on")),
    aliases=("transformation_2d",),
    doc="Transformation 2D: affine resampling with wrap-around (tiling) addressing."))
