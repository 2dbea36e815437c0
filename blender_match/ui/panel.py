"""The "Match" panel, in the sidebar (N) of the 3D Viewport and of the Shader Editor: photo, graph,
quality, size, device, Match / Cancel with a progress bar (stage, time left), then the active
matched material: its result, the graphs an automatic match ranked next (a button each, to match
them instead), Re-render at another size, its parameter sliders with Apply, and
Export for a game engine. One draw function (``draw_match_panel``), two thin Panel classes.
"""

import bpy

from ..blender import addon, match_job, parameters
from ..vocabulary import QUALITY_NAMES


def _loss_text(loss) -> str:
    return f"{loss:.4g}" if isinstance(loss, (int, float)) else "?"


def draw_photo_settings(layout, settings):
    col = layout.column(align=True)
    col.row(align=True).prop(settings, "photo_source", expand=True)
    if settings.photo_source == 'FILE':
        col.prop(settings, "photo_path", text="")
    else:
        col.prop(settings, "photo_image", text="")


def draw_match_settings(layout, settings):
    col = layout.column()
    col.prop(settings, "graph_family", text="Family")
    col.template_icon_view(settings, "graph", show_labels=True, scale=5.0, scale_popup=4.0)
    col.prop(settings, "graph", text="Graph")
    col.prop(settings, "quality")
    col.prop(settings, "size")
    col.prop(settings, "device")
    col.prop(settings, "calibrate")
    col.prop(settings, "match_scale")
    row = col.row(align=True)
    row.prop(settings, "tiling")
    row.prop(settings, "pack", text="Pack", toggle=True)


def draw_job(layout, job):
    """The running job: its progress bar (stage and time left) and the Cancel button."""
    col = layout.column(align=True)
    col.progress(factor=job.fraction, type='BAR', text=job.progress_text())
    col.operator("blender_match.cancel", text="Cancel", icon='CANCEL')


def draw_last(layout, last: dict | None):
    """The outcome of the scene's last job (an error stays until the next job)."""
    if not last:
        return
    if last.get("state") == "failed":
        box = layout.box()
        box.alert = True
        box.label(text="Last job failed:", icon='ERROR')
        for line in _wrap(last.get("error") or last.get("message") or "", 48):
            box.label(text=line)
    elif last.get("state") == "cancelled":
        layout.label(text="Cancelled: nothing was changed", icon='INFO')


def _wrap(text: str, width: int):
    words, line, lines = text.split(), "", []
    for word in words:
        if line and len(line) + 1 + len(word) > width:
            lines.append(line)
            line = word
        else:
            line = f"{line} {word}".strip()
    if line:
        lines.append(line)
    return lines[:6]


def draw_alternatives(layout, record: dict, busy: bool):
    """An automatic match's alternatives, the graphs its ranking put next after the kept one (its
    near-ties), each a button that matches the same photo with that graph at the same quality, into
    a new material; nothing for a named match or when the record does not say the photo."""
    names = [name for name in record.get("alternatives") or () if isinstance(name, str)]
    photo, image = record.get("photo"), record.get("photo_image")
    if not names or not (photo or image):
        return
    col = layout.column(align=True)
    col.label(text="Also close:")
    row = col.row(align=True)
    row.enabled = not busy
    ranked = [record.get("graph"), *names]  # the ranking's top 3: each new material offers the other two
    for name in names:
        op = row.operator("blender_match.match_photo", text=addon.graph_title(name), icon_value=addon.graph_icon(name))
        op.graph = name
        op.alternatives = ",".join(n for n in ranked if isinstance(n, str) and n != name)
        if image:
            op.image = image
        else:
            op.filepath = photo
        if record.get("quality") in QUALITY_NAMES:
            op.quality = record["quality"]


def draw_material(layout, context, settings, material, record: dict, busy: bool):
    """The active matched material: result, an automatic match's alternatives, Re-render,
    parameters and Apply, Export."""
    box = layout.box()
    box.label(text=material.name, icon='MATERIAL')
    col = box.column(align=True)
    col.label(text=f"Graph: {record.get('graph', '?')}")
    col.label(text=f"Loss: {_loss_text(record.get('loss'))}    Size: {record.get('size', '?')} px")
    last = match_job.LAST.get(addon.scene_key(context.scene)) or {}
    if last.get("material") == material.name and isinstance(last.get("seconds"), (int, float)):
        col.label(text=f"Time: {addon.format_seconds(last['seconds'])}")
    draw_alternatives(box, record, busy)

    row = box.row(align=True)
    row.enabled = not busy
    row.prop(settings, "rerender_size", text="")
    op = row.operator("blender_match.rerender", text="Re-render", icon='FILE_REFRESH')
    op.size = settings.rerender_size

    items = getattr(material, parameters.COLLECTION)
    sub = box.column(align=True)
    sub.label(text="Parameters", icon='PROPERTIES')
    if len(items):
        for item in items:
            if item.kind == 'COLOR':
                sub.prop(item, "color", text=item.title)
            elif item.unit_range:
                sub.prop(item, "value", text=item.title, slider=True)
            else:
                sub.prop(item, "value_wide", text=item.title)
        row = box.row(align=True)
        row.enabled = not busy
        row.operator("blender_match.apply_parameters", text="Apply", icon='CHECKMARK')
        row.operator("blender_match.reset_parameters", text="", icon='LOOP_BACK')
    else:
        sub.label(text="No editable parameters")
        sub.operator("blender_match.reset_parameters", text="Load Parameters", icon='LOOP_BACK')

    export = box.column(align=True)
    export.label(text="Export", icon='EXPORT')
    row = export.row(align=True)
    row.prop(settings, "export_preset", text="")
    row.prop(settings, "export_size", text="")
    row = export.row(align=True)
    row.prop(settings, "export_format", text="")
    row.prop(settings, "export_high_depth", text="High Depth", toggle=True)
    op = export.operator("blender_match.export_maps", text="Export Maps", icon='EXPORT')
    op.preset = settings.export_preset
    op.size = 0 if settings.export_size == 'SAME' else addon.SIZES[settings.export_size]
    op.file_format = settings.export_format
    op.bits = {("PNG", False): 8, ("PNG", True): 16, ("OPEN_EXR", False): 16,
               ("OPEN_EXR", True): 32}[(settings.export_format, bool(settings.export_high_depth))]


def draw_match_panel(layout, context):
    """The whole Match panel into ``layout`` (a UILayout, or the tests' recorder)."""
    scene = context.scene
    settings = getattr(scene, "blender_match", None)
    if settings is None:
        layout.label(text="Blender Match is not registered", icon='ERROR')
        return
    job = match_job.running_job(scene)

    settings_col = layout.column()
    settings_col.enabled = job is None
    draw_photo_settings(settings_col, settings)
    draw_match_settings(settings_col, settings)

    if job is not None:
        draw_job(layout, job)
    else:
        layout.operator("blender_match.match_photo", text="Match", icon='PLAY')
        obj = addon.active_object(context)
        if obj is None or not hasattr(obj.data, "materials"):
            layout.label(text="No active mesh: the material will not be assigned", icon='INFO')
    draw_last(layout, match_job.LAST.get(addon.scene_key(scene)))

    material = addon.active_material(context)
    record = parameters.stored_record(material)
    if material is not None and record is not None:
        draw_material(layout, context, settings, material, record, busy=job is not None)


class _MatchPanel:
    bl_label = "Match"
    bl_region_type = 'UI'
    bl_category = "Match"

    def draw(self, context):
        draw_match_panel(self.layout, context)


class BLENDER_MATCH_PT_view3d(_MatchPanel, bpy.types.Panel):
    bl_idname = "BLENDER_MATCH_PT_view3d"
    bl_space_type = 'VIEW_3D'


class BLENDER_MATCH_PT_shader_editor(_MatchPanel, bpy.types.Panel):
    bl_idname = "BLENDER_MATCH_PT_shader_editor"
    bl_space_type = 'NODE_EDITOR'

    @classmethod
    def poll(cls, context):
        space = getattr(context, "space_data", None)
        return space is not None and space.type == 'NODE_EDITOR' and space.tree_type == 'ShaderNodeTree'


classes = (BLENDER_MATCH_PT_view3d, BLENDER_MATCH_PT_shader_editor)
