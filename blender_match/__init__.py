"""blender_match: match a photo of a flat material with a procedural material, in Blender.

This file is the Blender add-on's entry point. Blender's own Python has no torch, so nothing here
(or in ``operators``/``ui``) imports the engine: matching runs in a worker process whose Python
has torch. bpy is imported only inside ``register``/``unregister``, so the command-line tool
(``python -m blender_match``) imports this package without Blender.
"""
from __future__ import annotations

import importlib

__version__ = "0.1.0"

# Modules whose ``classes`` tuple holds the bpy classes to register, in order.
_CLASS_MODULES = ("operators", "ui")


def _classes():
    for name in _CLASS_MODULES:
        module = importlib.import_module(f"{__name__}.{name}")
        yield from getattr(module, "classes", ())


def register():
    """Register the add-on's classes with Blender."""
    import bpy

    for cls in _classes():
        bpy.utils.register_class(cls)


def unregister():
    """Unregister in reverse order; leaves nothing behind."""
    import bpy

    for cls in reversed(list(_classes())):
        bpy.utils.unregister_class(cls)
