"""blender_match: match a photo of a flat material with a procedural material, in Blender.

This file is the Blender add-on's entry point. Blender's own Python has no torch, so nothing here
(or in ``operators``/``ui``) imports the engine: matching runs in a worker process whose Python
has torch. bpy is imported only inside ``register``/``unregister``, so the command-line tool
(``python -m blender_match``) imports this package without Blender.
"""
from __future__ import annotations

import importlib

from .version import __version__

__all__ = ["__version__", "register", "unregister"]

# Modules whose ``classes`` tuple holds the bpy classes to register, in order. A module may also
# have ``register()``/``unregister()`` for what is not a class (properties added to Blender's types),
# run after its classes are registered and before they are unregistered.
_CLASS_MODULES = ("preferences", "blender.properties", "operators", "ui")


def _modules():
    for name in _CLASS_MODULES:
        yield importlib.import_module(f"{__name__}.{name}")


def _classes():
    for module in _modules():
        yield from getattr(module, "classes", ())


def register():
    """Register the add-on's classes with Blender."""
    import bpy  # here, not at the top: the command line imports this package without Blender

    for module in _modules():
        for cls in getattr(module, "classes", ()):
            bpy.utils.register_class(cls)
        hook = getattr(module, "register", None)
        if hook is not None:
            hook()


def unregister():
    """Stop running jobs, then unregister in reverse order; leaves nothing behind."""
    import bpy  # here, not at the top: the command line imports this package without Blender

    from .blender import match_job  # imports bpy too

    match_job.shutdown()
    for module in reversed(list(_modules())):
        hook = getattr(module, "unregister", None)
        if hook is not None:
            hook()
        for cls in reversed(getattr(module, "classes", ())):
            if getattr(cls, "is_registered", True):
                bpy.utils.unregister_class(cls)
