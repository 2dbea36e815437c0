"""Declarations of the library normal / height / relief nodes (see functional/library_normal.py)."""
from .. import functional as F
from ..functional.library_normal import AO_MODELS
from .registry import register
from .spec import Input, NodeSpec, Param

NA = "non_atomic"
FORMAT = Param("normal_format", 0, kind="enum", choices=(0, 1), doc="0 DirectX, 1 OpenGL")

register(NodeSpec(
    "normal_combine", NA, F.normal_combine,
    inputs=(Input("input", "color"), Input("input_1", "color")), outputs=("normal",),
    params=(Param("blend_quality", 0, kind="enum", choices=(0, 1), doc="0 fast (whiteout), 1 high (RNM)"),),
    doc="Normal Combine: detail normal on a base normal."))

register(NodeSpec(
    "normal_blend", NA, F.normal_blend,
    inputs=(Input("normalbg", "color"), Input("normalfg", "color"), Input("mask", "gray", optional=True)),
    outputs=("normal_blend",),
    params=(Param("opacity", 1.0), Param("use_mask", True, kind="bool")),
    doc="Normal Blend: foreground normal over background normal, renormalised."))

register(NodeSpec(
    "normal_normalise", NA, F.normal_normalise,
    inputs=(Input("input", "color"),), aliases=("normal_normalize",),
    doc="Normal Normalise: unit-length normals."))

register(NodeSpec(
    "normal_to_height", NA, F.normal_to_height,
    inputs=(Input("input", "color"),), outputs=("height",),
    params=(FORMAT, Param("relief_balance", (0.5, 0.5, 0.5), size=3, doc="low, mid, high frequency weights"),
            Param("opacity", 1.0, doc="relief contrast around 0.5")),
    doc="Normal to Height: FFT integration of a normal map."))

register(NodeSpec(
    "curvature", NA, F.curvature,
    inputs=(Input("input", "color"),),
    params=(FORMAT, Param("intensity", 1.0, 0.0, 10.0)),
    doc="Curvature: divergence of a normal map, 0.5 flat."))

register(NodeSpec(
    "curvature_smooth", NA, F.curvature_smooth,
    inputs=(Input("input", "color"),), outputs=("height",),
    params=(FORMAT,),
    doc="Curvature Smooth: multi-scale normalised curvature."))

register(NodeSpec(
    "hbao", NA, F.hbao,
    inputs=(Input("input"),),
    params=(Param("height_depth", 0.1), Param("radius", 1.0),
            Param("quality", 4, kind="enum", choices=(4, 8, 16), doc="directions"),
            Param("use_world_units", False, kind="bool"),
            Param("surface_size", 100.0, 1.0, 1000.0, doc="cm, world units only"),
            Param("height_scale", 1.0, 0.0, 100.0, doc="cm, world units only")),
    doc="HBAO: horizon-based ambient occlusion of a height map."))

register(NodeSpec(
    "ambient_occlusion_2", NA, F.ambient_occlusion,
    inputs=(Input("source"),), outputs=("ambient_occlusion",),
    params=(Param("height_depth", 0.15, doc="depth scale (ours; 0.15 is the reference's)"),
            Param("spreading", 0.15, doc="reach: a Blur HQ of spreading x 128"),
            Param("equalizer", (0.0, 0.0, 0.0), -0.5, 0.5, size=3,
                  doc="low, mid, high bands (0 leaves a band as it is)"),
            Param("levels", (0.0, 0.5, 1.0), size=3, doc="final Levels: in low, mid, high"),
            Param("model", 0, kind="enum", choices=tuple(AO_MODELS),
                  doc="0 Substance's (the MATch reference's), 1 three blurs (ours, our library's)")),
    doc="Ambient Occlusion (blur-based, the older node)."))

register(NodeSpec(
    "edge_detect", NA, F.edge_detect,
    inputs=(Input("input"),),
    params=(Param("edge_width", 2.0, 0.0, 16.0, doc="256-px pixels"),
            Param("edge_roundness", 4.0, 0.0, 16.0, doc="256-px pixels"),
            Param("tolerance", 0.0), Param("invert", False, kind="bool")),
    doc="Edge Detect: contour lines of a mask."))

register(NodeSpec(
    "bevel", NA, F.bevel,
    inputs=(Input("input"),), outputs=("height", "normal"),
    params=(Param("distance", 0.5, -1.0, 1.0, doc="x 0.1 image widths; negative bevels outwards"),
            Param("smoothing", 0.0, 0.0, 5.0), Param("normal_intensity", 10.0, 0.0, 50.0), FORMAT),
    doc="Bevel: height ramp and normal around a mask's shapes."))

register(NodeSpec(
    "basecolor_metallic_roughness_to_diffuse_specular_glossiness", NA,
    F.metallic_roughness_to_specular_glossiness,
    inputs=(Input("basecolor", "color"), Input("metallic", "gray"), Input("roughness", "gray")),
    outputs=("diffuse", "specular", "glossiness"),
    doc="PBR converter: metallic/roughness to specular/glossiness."))
