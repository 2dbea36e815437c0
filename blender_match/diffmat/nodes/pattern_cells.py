"""Declarations of the cellular generators (see functional/pattern_cells.py)."""
from .. import functional as F
from .registry import register
from .spec import NodeSpec, Param

GEN = ("size", "seed", "device", "dtype")


def _cells(extra=()):
    return (Param("scale", 8, 1, 256, kind="int", doc="cells per image side"),
            Param("disorder", 0.0, 0.0, 1.0, doc="turns the feature points around their cells")) + extra


register(NodeSpec("cells_1", "generator", F.cells_soft, params=_cells(), context=GEN,
                  doc="Cells 1: cushion-like cells with dark borders."))
register(NodeSpec("cells_2", "generator", F.cells_distance, params=_cells(), context=GEN,
                  doc="Cells 2: distance to the nearest feature point (Worley F1)."))
register(NodeSpec("cells_3", "generator", F.cells_cracks,
                  params=_cells((Param("width", 0.06, 0.0, 0.3, doc="crack width, cells"),)), context=GEN,
                  doc="Cells 3: flat cells separated by thin cracks."))
register(NodeSpec("cells_4", "generator", F.cells_flat, params=_cells(), context=GEN,
                  doc="Cells 4: Voronoi mosaic of random gray levels."))
register(NodeSpec("alveolus", "generator", F.alveolus_pattern,
                  params=_cells((Param("wall", 0.1, 0.0, 0.5, doc="wall thickness, cells"),
                                 Param("depth", 0.8, 0.0, 1.0, doc="depth of the pits"))),
                  context=GEN, doc="Alveolus: a honeycomb of rounded pits."))
