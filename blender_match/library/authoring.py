"""Shared vocabulary of the material sources (``library/sources/*.py``): blend-mode names, gradient
keys, and constant maps pinned so the optimiser cannot move them."""
from __future__ import annotations

from ..translator.runtime import SbsGraph
from ..vocabulary import AUTHORED_USAGES
from .expressions import const

# Substance's blending-mode codes (the blend node's ``blendingmode``)
COPY, ADD, SUBTRACT, MULTIPLY, ADD_SUB, MAX, MIN, SWITCH, DIVIDE, OVERLAY, SCREEN, SOFT_LIGHT = range(12)


def gradient_keys(stops) -> dict:
    """Gradient-map parameters from ``[(position, (r, g, b)), …]`` (opaque keys)."""
    return {"positions": [p for p, _ in stops], "colors": [c for _, rgb in stops for c in (*rgb, 1.0)]}


def constant_map(g: SbsGraph, name: str, value: float) -> str:
    """A flat grayscale map (a uniform node) whose level is bound to a constant, so it is written to
    the .sbs as a fixed value and never optimised (a dielectric's metallic 0, a metal's 1)."""
    color = (value, value, value, 1.0)
    g.add(name, "uniform", colorswitch=False, outputcolor=color)
    g.bind(name, "outputcolor", const(color).graph())
    return name


def set_material_outputs(g: SbsGraph, ambient_occlusion: str | None = None):
    """Name the five material maps after the nodes of the same names (and optionally the ambient
    occlusion node)."""
    for usage in AUTHORED_USAGES:
        g.set_output(usage, usage)
    if ambient_occlusion:
        g.set_output("ambientocclusion", ambient_occlusion)
