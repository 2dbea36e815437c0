"""Stateless functional ops of DiffMat (like ``torch.nn.functional``).

Every public name in a submodule's ``__all__`` is re-exported here, so ``F.levels`` or
``F.perlin_noise`` is one attribute away. Submodules hold one family of ops each.
"""
import importlib
import pkgutil

__all__: list[str] = []
for _info in sorted(pkgutil.iter_modules(__path__), key=lambda m: m.name):
    _module = importlib.import_module(f"{__name__}.{_info.name}")
    for _name in getattr(_module, "__all__", ()):
        globals()[_name] = getattr(_module, _name)
        __all__.append(_name)
