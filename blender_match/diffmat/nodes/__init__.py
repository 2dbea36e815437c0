"""Node declarations and the parameter-holding Node module (like ``torch.nn``).

Importing this package registers every node: each submodule other than the machinery
(spec, registry, module) declares the NodeSpecs of one family of functional ops.
"""
import importlib
import pkgutil

from .module import EvalContext, Node
from .registry import all_names, all_specs, get_spec, has_spec, register
from .spec import Input, NodeSpec, Param

_MACHINERY = {"spec", "registry", "module"}
for _info in sorted(pkgutil.iter_modules(__path__), key=lambda m: m.name):
    if _info.name not in _MACHINERY:
        importlib.import_module(f"{__name__}.{_info.name}")

__all__ = ["EvalContext", "Input", "Node", "NodeSpec", "Param", "all_names", "all_specs",
           "get_spec", "has_spec", "register"]
