"""The add-on's preferences (Preferences > Add-ons > Blender Match): the worker's Python, the
default device, and the buttons that set up the backend and test the worker.

Matching needs a Python with torch (Blender's has none): either "Set up backend" creates one in
the add-on's user folder (a virtual environment, torch from PyPI), or "Worker Python" names an
existing one (a Python where ``pip install blender-match`` was done). "User Library" names the
folder of the user's own materials (``blender-match library add``; ``addon.apply_user_library``).
"""

import bpy
from bpy.props import EnumProperty, StringProperty

from .blender import addon, match_job
from .library.catalog import USER
from .vocabulary import DEFAULT_DEVICE


def draw_preferences(prefs, layout, context):
    """The preferences' layout (shared with the tests' layout recorder)."""
    layout.prop(prefs, "worker_python")
    layout.prop(prefs, "default_device")
    layout.prop(prefs, "user_library")
    users = [name for name, graph in addon.library_graphs().items() if graph["library"] == USER]
    layout.label(text=f"{len(users)} graph(s) of your own in {addon.user_library_dir()} "
                      "(add them with: blender-match library add PATH.sbs|FOLDER)", icon='ASSET_MANAGER')

    box = layout.box()
    box.label(text="Backend", icon='CONSOLE')
    try:
        python = addon.worker_python(context)
        box.label(text=f"Worker Python: {python}", icon='CHECKMARK')
    except addon.AddonError as exc:
        box.label(text=str(exc), icon='ERROR')
    box.label(text=f"Backend folder: {addon.backend_dir()}")
    box.prop(prefs, "pip_arguments")
    setup = match_job.SERVICES.get("setup")
    row = box.row()
    if setup is not None and not setup.done:
        row.progress(factor=setup.fraction, type='BAR', text=setup.progress_text())
        row.operator("blender_match.cancel", text="Cancel", icon='CANCEL').target = 'SETUP'
    else:
        row.operator("blender_match.setup_backend", text="Set up backend", icon='IMPORT')
        row.operator("blender_match.probe_worker", text="Test worker", icon='PLAY')
        if setup is not None:
            box.label(text=setup.message, icon='CHECKMARK' if setup.state == "finished" else 'ERROR')
    probe = match_job.SERVICES.get("probe")
    if probe is not None:
        if not probe.done:
            box.label(text="Testing the worker…", icon='TIME')
        else:
            col = box.column(align=True)
            icon = 'CHECKMARK' if probe.state == "finished" else 'ERROR'
            for i, part in enumerate(probe.message.split("; ")):
                col.label(text=part, icon=icon if i == 0 else 'BLANK1')


class BLENDER_MATCH_AddonPreferences(bpy.types.AddonPreferences):
    bl_idname = addon.ADDON_PACKAGE

    worker_python: StringProperty(
        name="Worker Python", subtype='FILE_PATH',
        description="A Python with torch and blender-match's requirements to run the matching "
                    "(empty: the backend set up below)")
    default_device: EnumProperty(name="Default Device", items=addon.DEVICE_ITEMS, default=DEFAULT_DEVICE,
                                 description="Where matches run unless the panel says otherwise")
    user_library: StringProperty(
        name="User Library", subtype='DIR_PATH', update=lambda self, context: addon.apply_user_library(context),
        description="Folder of your own .sbs materials (blender-match library add), searched by automatic "
                    "matching together with the built-in library (empty: $BLENDER_MATCH_LIBRARY or the "
                    "user-data folder)")
    pip_arguments: StringProperty(
        name="pip Arguments",
        description="Extra arguments for pip when setting up the backend (e.g. --index-url "
                    "https://download.pytorch.org/whl/cu124 for another torch build)")

    def draw(self, context):
        draw_preferences(self, self.layout, context)


classes = (BLENDER_MATCH_AddonPreferences,)


def register():
    addon.apply_user_library()
