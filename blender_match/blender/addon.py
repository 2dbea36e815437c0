"""What the add-on's operators, panels and preferences share: its package name, preferences, the
backend folder, the worker's Python, the library graphs (``library.catalog``, which imports
without torch, which Blender's Python lacks) and their thumbnails, result folders. Imported only
inside Blender.
"""
from __future__ import annotations

import os
import re
import time
from pathlib import Path

import bpy
import bpy.utils.previews

from ..errors import BlenderMatchError
from ..library.catalog import (
    FAMILIES,
    USER_LIBRARY_ENV,
    LibraryError,
    family_of,
    library_entry,
    library_names,
    thumbnail_file,
    user_library_dir,
)
from ..vocabulary import DEFAULT_DEVICE, DEVICES, QUALITIES
from ..worker.client import find_worker_python

# The add-on's top package: "blender_match" as a plain module, "bl_ext.<repo>.blender_match" as an
# extension. AddonPreferences.bl_idname and extension_path_user need it.
ADDON_PACKAGE = __package__.rpartition(".")[0]
PACKAGE_DIR = Path(__file__).resolve().parents[1]

NO_BACKEND = "No matching backend: set it up in Preferences > Add-ons > Blender Match"
SIZES = {"1K": 1024, "2K": 2048, "4K": 4096}
SIZE_ITEMS = [("1K", "1K", "1024 x 1024 pixels"), ("2K", "2K", "2048 x 2048 pixels"),
              ("4K", "4K", "4096 x 4096 pixels")]
QUALITY_ITEMS = [(q.name, q.label, q.description) for q in QUALITIES]
DEVICE_ITEMS = [(d.name, d.label, d.description) for d in DEVICES]
PREFERENCES_DEVICE = ("default", "Preferences", "The default device set in the add-on's preferences")
RESULT_FOLDER = "blender_match"


class AddonError(BlenderMatchError):
    """Something the user has to fix before the add-on can act (the message says what)."""


# --- preferences and the worker ------------------------------------------------------------------


def preferences(context=None):
    """The add-on's preferences, or None when it is registered without being enabled as an
    add-on (e.g. ``blender_match.register()`` in a script)."""
    context = context or bpy.context
    addon = context.preferences.addons.get(ADDON_PACKAGE)
    return addon.preferences if addon is not None else None


def backend_dir(create: bool = False) -> Path:
    """The folder of the backend's virtual environment: the extension's user folder, or, for an
    add-on loaded as a plain module (no extension to own a folder), one under the user's scripts."""
    try:
        return Path(bpy.utils.extension_path_user(ADDON_PACKAGE, path="backend", create=create))
    except ValueError:  # "The package does not name an extension"
        folder = Path(bpy.utils.user_resource("SCRIPTS")) / "blender_match_backend"
        if create:
            folder.mkdir(parents=True, exist_ok=True)
        return folder


def worker_python(context=None) -> str:
    """The Python that runs the worker: the preference, else the backend's; AddonError if none."""
    prefs = preferences(context)
    preferred = (prefs.worker_python if prefs is not None else "").strip()
    if preferred:
        preferred = bpy.path.abspath(preferred)
    python = find_worker_python(preferred or None, backend_dir())
    if python is None:
        if preferred:
            raise AddonError(f"{NO_BACKEND} (the worker Python {preferred} set there does not exist "
                             "or cannot be run)")
        raise AddonError(NO_BACKEND)
    return python


def default_device(context=None) -> str:
    prefs = preferences(context)
    return prefs.default_device if prefs is not None else DEFAULT_DEVICE


def resolve_device(device: str, context=None) -> str:
    return default_device(context) if device in ("default", "", None) else device


# --- the library graphs --------------------------------------------------------------------------

# the user library Blender was started with ($BLENDER_MATCH_LIBRARY), restored when the
# preference is emptied
_STARTUP_LIBRARY = os.environ.get(USER_LIBRARY_ENV)


def apply_user_library(context=None) -> Path:
    """Point the library's catalogue, and so the graph menu and every worker started from here (they
    inherit the environment), at the preferences' user library folder; an empty preference keeps
    the folder Blender was started with (``$BLENDER_MATCH_LIBRARY``, else the user-data default).
    The menu and thumbnails are read again. The folder in use."""
    prefs = preferences(context)
    folder = str(getattr(prefs, "user_library", "") or "").strip()
    if folder:
        os.environ[USER_LIBRARY_ENV] = str(Path(bpy.path.abspath(folder)).expanduser())
    elif _STARTUP_LIBRARY is not None:
        os.environ[USER_LIBRARY_ENV] = _STARTUP_LIBRARY
    else:
        os.environ.pop(USER_LIBRARY_ENV, None)
    release_previews()
    return user_library_dir()


_GRAPHS: dict | None = None


def library_graphs() -> dict[str, dict]:
    """Library graph name -> its metadata (name, description, exposed, exposed_params), from the
    library's catalogue, sorted by name; a graph whose metadata cannot be read is left out."""
    global _GRAPHS
    if _GRAPHS is None:
        graphs = {}
        for name in library_names():
            try:
                entry = library_entry(name)
            except LibraryError:
                continue
            graphs[name] = {"name": entry.get("name", name), "description": entry.get("description", ""),
                            "exposed": list(entry.get("exposed") or []),
                            "exposed_params": dict(entry.get("exposed_params") or {}),
                            "library": entry["library"], "family": graph_family(entry)}
        _GRAPHS = graphs
    return _GRAPHS


ALL_FAMILIES = "ALL"
USER_FAMILY = "USER"


def graph_family(entry: dict) -> str:
    """The picker's category of a library entry: its family (``catalog.FAMILIES``), or USER_FAMILY
    for the user's own graphs (which declare none)."""
    return family_of(entry) or USER_FAMILY


def family_items() -> list[tuple[str, str, str]]:
    """The graph picker's categories: all, then each family that has a graph, then the user library."""
    present = {entry["family"] for entry in library_graphs().values()}
    items = [(ALL_FAMILIES, "All", "Every library graph")]
    items += [(key, label, f"{label} graphs") for key, label in FAMILIES.items() if key in present]
    if USER_FAMILY in present:
        items.append((USER_FAMILY, "User Library", "The graphs added to your own library"))
    return items


def graph_title(name: str) -> str:
    return name.replace("_", " ").title()


def graph_source_name(source: str | None) -> str | None:
    """The library graph a stored "source" names (a name, or a path to a library .sbs), or None."""
    if not source:
        return None
    stem = Path(source).name
    stem = stem[:-4] if stem.lower().endswith(".sbs") else stem
    return stem if stem in library_graphs() else None


_PREVIEWS = None


def graph_icon(name: str) -> int:
    """The icon id of a library graph's thumbnail (``graphs/<name>.png`` of its library), 0 when there
    is none."""
    global _PREVIEWS
    try:
        path = thumbnail_file(name)
    except LibraryError:
        return 0
    if not path.is_file():
        return 0
    if _PREVIEWS is None:
        _PREVIEWS = bpy.utils.previews.new()
    if name not in _PREVIEWS:
        _PREVIEWS.load(name, str(path), "IMAGE")
    return _PREVIEWS[name].icon_id


def release_previews() -> None:
    global _PREVIEWS, _GRAPHS
    if _PREVIEWS is not None:
        bpy.utils.previews.remove(_PREVIEWS)
        _PREVIEWS = None
    _GRAPHS = None


# --- context -------------------------------------------------------------------------------------


def active_object(context):
    obj = getattr(context, "active_object", None)
    if obj is None and getattr(context, "view_layer", None) is not None:
        obj = context.view_layer.objects.active
    return obj


def active_material(context):
    obj = active_object(context)
    return obj.active_material if obj is not None else None


def scene_key(scene) -> int:
    """A key for one scene that survives renames and undo (the registry of running jobs)."""
    return scene.session_uid


def redraw_ui(context=None) -> None:
    """Redraw the panels showing the add-on (its progress bar, the preferences)."""
    wm = (context or bpy.context).window_manager
    if wm is None:
        return
    for window in wm.windows:
        screen = window.screen
        if screen is None:
            continue
        for area in screen.areas:
            if area.type == "PREFERENCES":
                area.tag_redraw()
            elif area.type in ("VIEW_3D", "NODE_EDITOR"):
                for region in area.regions:  # the sidebar only, not the (costly) viewport itself
                    if region.type == "UI":
                        region.tag_redraw()


# --- result folders ------------------------------------------------------------------------------


def blend_is_saved() -> bool:
    return bool(bpy.data.filepath)


def results_root() -> Path:
    """``//blender_match`` next to the saved .blend, else a folder in Blender's session temporary
    folder (removed when Blender quits: the caller packs the images then)."""
    if bpy.data.filepath:
        return Path(bpy.path.abspath("//" + RESULT_FOLDER))
    return Path(bpy.app.tempdir or os.environ.get("TMPDIR", "/tmp")) / RESULT_FOLDER


def folder_stem(text: str) -> str:
    stem = re.sub(r"[^\w.-]+", "_", Path(str(text)).stem if str(text).lower().endswith(".sbs") else str(text))
    return stem.strip("._") or "material"


def new_result_folder(stem: str) -> tuple[Path, list[Path]]:
    """Create a new, empty ``<root>/<stem>_<timestamp>[_n]`` folder (never an existing one); the
    folder and the list of folders created for it (to remove if the job leaves nothing)."""
    root = results_root()
    created: list[Path] = []
    missing = []
    parent = root
    while not parent.exists():
        missing.append(parent)
        if parent.parent == parent:
            break
        parent = parent.parent
    try:
        root.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise AddonError(f"cannot create the result folder {root}: {exc.strerror or exc}") from None
    created.extend(reversed(missing))
    base = f"{folder_stem(stem)}_{time.strftime('%Y%m%d-%H%M%S')}"
    for n in range(1, 1000):
        folder = root / (base if n == 1 else f"{base}_{n}")
        try:
            folder.mkdir()
        except FileExistsError:
            continue
        except OSError as exc:
            raise AddonError(f"cannot create the result folder {folder}: {exc.strerror or exc}") from None
        return folder, [folder, *reversed(created)]
    raise AddonError(f"{root}: no free folder name for {base}")


def format_seconds(seconds) -> str:
    if seconds is None:
        return ""
    seconds = max(0.0, float(seconds))
    if seconds < 1:
        return "<1 s"
    if seconds < 60:
        return f"{seconds:.0f} s"
    minutes, secs = divmod(int(round(seconds)), 60)
    if minutes < 60:
        return f"{minutes} min {secs} s" if secs else f"{minutes} min"
    hours, minutes = divmod(minutes, 60)
    return f"{hours} h {minutes} min"
