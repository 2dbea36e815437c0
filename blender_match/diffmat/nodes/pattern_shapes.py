"""Declarations of the shape-based pattern generators (see functional/pattern_shapes.py)."""
from .. import functional as F
from ..functional.pattern_shapes import SHAPES
from .registry import register
from .spec import NodeSpec, Param

GEN = ("size", "seed", "device", "dtype")
GEN_NOSEED = ("size", "device", "dtype")
SHAPE_DOC = ", ".join(f"{i} {n}" for i, n in enumerate(SHAPES))

_SCRATCHES = (Param("amount", 6, 1, 64, kind="int", doc="cells per image side (two lines per cell)"),
              Param("length", 1.4, 0.0, 2.0, doc="line length, cells"),
              Param("width", 0.02, 0.0, 0.2, doc="line width, cells"),
              Param("angle", 0.0, 0.0, 1.0, doc="turns"),
              Param("angle_random", 0.5, 0.0, 1.0, doc="turns of random spread"),
              Param("length_random", 0.5, 0.0, 1.0),
              Param("luminance_random", 0.5, 0.0, 1.0),
              Param("mask_random", 0.0, 0.0, 1.0, doc="fraction of lines hidden"))

register(NodeSpec(
    "shape", "generator", F.shape_pattern,
    params=(Param("pattern", 0, kind="enum", choices=tuple(range(len(SHAPES))), doc=SHAPE_DOC),
            Param("tiling", 1, 1, 16, kind="int", doc="copies per image side"),
            Param("pattern_specific", 0.5, doc="shape-dependent control (bevel, frequency, offset…)"),
            Param("scale", 1.0, 0.0, 1.0, doc="1 fills the tile"),
            Param("size_xy", (1.0, 1.0), 0.0, 1.0, size=2,
                  doc="non-uniform size (Substance's 'Size'; renamed: 'size' is the output size)"),
            Param("angle", 0.0, 0.0, 1.0, doc="rotation, turns"),
            Param("rotation_45", False, kind="bool", doc="adds 1/8 turn")),
    context=GEN,
    doc="Shape: one procedural shape (square, disc, bell, …) repeated tiling × tiling times."))

register(NodeSpec(
    "polygon_1", "generator", F.polygon_pattern,
    params=(Param("sides", 3, 3, 32, kind="int"),
            Param("tiling", 1, 1, 16, kind="int"),
            Param("scale", 0.8, 0.0, 1.0, doc="circumradius as a fraction of half the tile"),
            Param("rotation", 0.0, 0.0, 1.0, doc="turns"),
            Param("gradient", 0.0, 0.0, 1.0, doc="0 flat … 1 fades from the centre to the edge"),
            Param("curve", 0.0, 0.0, 1.0, doc="rounds the gradient's falloff")),
    context=GEN,
    doc="Polygon 1: a regular polygon, optionally with a gradient fill."))

register(NodeSpec(
    "gradient_linear_1", "generator", F.linear_gradient,
    params=(Param("tiling", 1, 1, 16, kind="int"),
            Param("rotation", 0.0, 0.0, 1.0, optimizable=False,
                  doc="turns, snapped to quarter turns (a ramp in another direction cannot tile)")),
    context=GEN_NOSEED,
    doc="Gradient Linear 1: a ramp from black (bottom) to white (top), turned, repeated tiling times."))

register(NodeSpec(
    "gradient_linear_2", "generator", F.mirrored_linear_gradient,
    params=(Param("tiling", 1, 1, 16, kind="int"),
            Param("rotation", 0.0, 0.0, 1.0, optimizable=False, doc="turns, snapped to quarter turns")),
    context=GEN_NOSEED,
    doc="Gradient Linear 2: a symmetric black-white-black ramp."))

register(NodeSpec(
    "gradient_linear_3", "generator", F.smooth_linear_gradient,
    params=(Param("tiling", 1, 1, 16, kind="int"),
            Param("rotation", 0.0, 0.0, 1.0, optimizable=False, doc="turns, snapped to quarter turns"),
            Param("position", 0.5, 0.0, 1.0, doc="where the white peak sits in each period")),
    context=GEN_NOSEED,
    doc="Gradient Linear 3: a smooth (cosine) black-white-black ramp."))

register(NodeSpec(
    "normal_color", "generator", F.normal_color,
    outputs=("normal_color",),
    params=(Param("direction", 0.0, 0.0, 1.0, doc="turns, 0 = +x"),
            Param("slope_angle", 0.0, 0.0, 0.25, doc="turns from the vertical"),
            Param("invert_y", False, kind="bool", doc="flip green (DirectX)")),
    context=GEN_NOSEED,
    doc="Normal Color: a flat, uniformly tilted normal map (RGBA)."))

register(NodeSpec(
    "stripes", "generator", F.stripes,
    params=(Param("number", 10, 1, 512, kind="int", doc="stripes per image"),
            Param("width", 0.5, 0.0, 1.0, doc="fraction of the period that is white"),
            Param("softness", 0.0, 0.0, 1.0, doc="edge softness"),
            Param("shift", 0, -64, 64, kind="int",
                  doc="slant: periods shifted over the image height (shift = number: 45 degrees)")),
    context=GEN_NOSEED,
    doc="Stripes: parallel bands."))

register(NodeSpec(
    "scratches_generator", "generator", F.scratches,
    params=_SCRATCHES,
    context=GEN,
    doc="Scratches Generator (simplified): scattered thin tapered lines."))

register(NodeSpec(
    "scratches_generator_normal", "generator", F.scratches_normal,
    outputs=("normal", "mask"),
    params=_SCRATCHES + (
        Param("normal_intensity", 0.5, 0.0, 1.0, doc="slope of the grooves"),
        Param("normal_format", 0, kind="enum", choices=(0, 1), doc="0 DirectX, 1 OpenGL")),
    context=GEN,
    doc="Scratches Generator (Normal): the scratches as a normal map of grooves, and their mask."))

register(NodeSpec(
    "creased", "generator", F.creased,
    params=(Param("scale", 4, 1, 32, kind="int"),
            Param("disorder", 0.0, 0.0, 1.0),
            Param("folds", 12, 1, 32, kind="int")),
    context=GEN,
    doc="Creased: crumpled-paper creases."))
