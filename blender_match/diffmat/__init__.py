"""DiffMat: differentiable procedural-material nodes in PyTorch (the MATch paper, section 5).

- ``diffmat.functional`` (as ``F``): stateless ops, one per node, plus tiling helpers;
- ``diffmat.nodes``: node declarations (NodeSpec), the registry, and the ``Node`` module that
  holds a node's parameters normalised in [0, 1];
- ``diffmat.graph.MaterialGraph``: the graph runtime;
- ``USAGES``: the material outputs a graph may name (``blender_match.vocabulary``'s).

The engine imports no bpy.
"""
from ..vocabulary import USAGES
from . import functional as F
from .errors import DiffMatError
from .graph import MaterialGraph
from .nodes import EvalContext, Node, all_specs, get_spec

__all__ = ["F", "DiffMatError", "EvalContext", "MaterialGraph", "Node", "USAGES", "all_specs", "get_spec"]
