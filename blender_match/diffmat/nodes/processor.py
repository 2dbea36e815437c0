"""Declarations of the programmable nodes: Pixel Processor and Value Processor (see
functional/processor.py). Their function graphs are parameters of kind "string" holding the
function graph's JSON text (``functional/function_graph.py`` describes the format)."""
from .. import functional as F
from ..functional.processor import DEFAULT_PERPIXEL, DEFAULT_VALUE_FUNCTION
from .registry import register
from .spec import Input, NodeSpec, Param

PIXEL_INPUTS = ("input",) + tuple(f"input_{i}" for i in range(1, 8))

register(NodeSpec(
    "pixelprocessor", "atomic", F.pixel_processor,
    inputs=tuple(Input(name, "any", optional=True) for name in PIXEL_INPUTS),
    params=(Param("perpixel", DEFAULT_PERPIXEL, kind="string",
                  doc="function graph (JSON) evaluated per pixel; $pos is the pixel position"),
            Param("colorswitch", True, kind="bool", doc="colour (True) or grayscale output")),
    context=("size", "seed", "device", "dtype"),
    doc="Pixel Processor: a function graph evaluated at every pixel, sampling up to 8 inputs."))

register(NodeSpec(
    "valueprocessor", "atomic", F.value_processor,
    params=(Param("function", DEFAULT_VALUE_FUNCTION, kind="string",
                  doc="function graph (JSON) evaluated once"),),
    context=("size", "seed", "device", "dtype"),
    doc="Value Processor: a function graph evaluated once, output as a uniform image of its value."))
