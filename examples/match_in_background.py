"""Match a photo in Blender without its interface, and save the result as a .blend.

    blender --background --python examples/match_in_background.py -- PHOTO GRAPH OUT.blend

PHOTO: the flash photo of a flat material sample; GRAPH: a library graph's name (plaster,
bricks, ...) or AUTO; OUT.blend: the file to write (its folder gets ``blender_match/<graph>_<time>/``
with the maps). The fitted material goes on the active object if it can hold materials, else on
a new plane. Optional environment variables:

    BLENDER_MATCH_PYTHON   the worker Python (one with torch and blender-match's requirements);
                           without it, the add-on's preference or its backend is used
    BLENDER_MATCH_QUALITY  draft, balanced (default) or best
    BLENDER_MATCH_SIZE     size of the maps in pixels (default 2048)
    BLENDER_MATCH_ITERATIONS  override the quality preset's iteration count (quick trials)

The add-on (the ``blender_match`` extension, or ``blender_match`` on Blender's module path) is
enabled if it is not already. Exit status 0 on success, 1 with the error message otherwise.
"""
import os
import sys
from pathlib import Path

import bpy  # first: with Blender as a Python module (pip's bpy), it puts addon_utils on the path
import addon_utils  # noqa: E402


def arguments():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(argv) != 3:
        sys.exit(f"usage: blender --background --python {Path(__file__).name} -- PHOTO GRAPH OUT.blend")
    return Path(argv[0]).resolve(), argv[1], Path(argv[2]).resolve()


def enable_addon() -> str:
    """The add-on's module name, enabled: the installed extension if there is one."""
    names = [m.__name__ for m in addon_utils.modules() if m.__name__.rpartition(".")[2] == "blender_match"]
    names = sorted(names, key=lambda n: not n.startswith("bl_ext.")) or ["blender_match"]
    for name in names:
        if name in bpy.context.preferences.addons:
            return name
    name = names[0]
    addon_utils.enable(name, default_set=True, handle_error=None)
    if name not in bpy.context.preferences.addons:
        sys.exit(f"cannot enable the {name} add-on: install the extension zip "
                 "(blender-match build-extension) or put blender_match on Blender's module path")
    return name


def target_object():
    """The active object if it can hold materials, else a new plane (made active)."""
    obj = bpy.context.view_layer.objects.active
    if obj is not None and hasattr(obj.data, "materials"):
        return obj
    bpy.ops.mesh.primitive_plane_add(size=2)
    return bpy.context.view_layer.objects.active


def main() -> int:
    photo, graph, out_blend = arguments()
    if not photo.is_file():
        print(f"{photo}: photo not found", file=sys.stderr)
        return 1
    module = enable_addon()
    python = os.environ.get("BLENDER_MATCH_PYTHON")
    if python:
        bpy.context.preferences.addons[module].preferences.worker_python = python
    # Save first: the maps then go next to the .blend (an unsaved file gets them in a temporary
    # folder, packed into the file).
    out_blend.parent.mkdir(parents=True, exist_ok=True)
    obj = target_object()
    bpy.ops.wm.save_as_mainfile(filepath=str(out_blend))
    try:
        bpy.ops.blender_match.match_photo(
            filepath=str(photo), graph=graph, size=int(os.environ.get("BLENDER_MATCH_SIZE", "2048")),
            quality=os.environ.get("BLENDER_MATCH_QUALITY", "balanced"),
            iterations=int(os.environ.get("BLENDER_MATCH_ITERATIONS", "0")), wait=True)
    except RuntimeError as exc:  # the operator's error report
        print(f"match failed: {str(exc).strip()}", file=sys.stderr)
        return 1
    material = bpy.data.objects[obj.name].active_material
    print(f"{obj.name}: {material.name} ({material['blender_match']['result_dir']})")
    bpy.ops.wm.save_mainfile()
    return 0


if __name__ == "__main__":
    code = main()
    sys.stdout.flush()
    sys.exit(code)
