"""``bpy.ops.blender_match.export_maps``: the active matched material's maps as a game engine's
texture set (``blender.export_presets``: glTF, Unreal, Unity), from its result folder::

    bpy.ops.blender_match.export_maps(preset='unreal', directory="//export", size=1024, bits=8,
                                      file_format='PNG')
"""

from pathlib import Path

import bpy
from bpy.props import BoolProperty, EnumProperty, IntProperty, StringProperty

from ..blender import addon, parameters
from ..blender.export_presets import export_maps
from ..errors import BlenderMatchError


class BLENDER_MATCH_OT_export_maps(bpy.types.Operator):
    """Export the active matched material's maps for a game engine"""

    bl_idname = "blender_match.export_maps"
    bl_label = "Export Maps"

    preset: EnumProperty(name="Preset", items=[("gltf", "glTF", "glTF 2.0 metallic-roughness"),
                                               ("unreal", "Unreal", "Unreal Engine (ORM, DirectX normal)"),
                                               ("unity", "Unity", "Unity URP/HDRP Lit")], default="gltf")
    size: IntProperty(name="Size", default=0, min=0, max=16384, description="Pixels (0: the maps' own size)")
    bits: IntProperty(name="Bits", default=8, min=8, max=32, description="PNG: 8 or 16; OpenEXR: 16 or 32")
    file_format: EnumProperty(name="Format", items=[("PNG", "PNG", ""), ("OPEN_EXR", "OpenEXR", "")], default="PNG")
    directory: StringProperty(name="Folder", subtype='DIR_PATH', options={'SKIP_SAVE'})
    name: StringProperty(name="Name", default="", options={'SKIP_SAVE'},
                         description="Files' stem (default: the graph's name)")
    overwrite: BoolProperty(name="Overwrite", default=False, options={'SKIP_SAVE'},
                            description="Replace existing files")

    @classmethod
    def poll(cls, context):
        if parameters.stored_record(addon.active_material(context)) is None:
            cls.poll_message_set("The active material was not made by Blender Match")
            return False
        return True

    def invoke(self, context, event):
        if not self.directory:
            record = parameters.stored_record(addon.active_material(context)) or {}
            folder = record.get("result_dir")
            self.directory = str(Path(folder).parent / "export") + "/" if folder else "//"
        context.window_manager.fileselect_add(self)
        return {'RUNNING_MODAL'}

    def execute(self, context):
        material = addon.active_material(context)
        record = parameters.stored_record(material) or {}
        result_dir = record.get("result_dir")
        if not result_dir or not Path(result_dir).is_dir():
            self.report({'ERROR'}, f"the maps of \"{material.name}\" are gone ({result_dir} does not exist, "
                                   "e.g. it was matched in an unsaved file): re-render it first")
            return {'CANCELLED'}
        if not self.directory:
            self.report({'ERROR'}, "choose a folder to export to")
            return {'CANCELLED'}
        out_dir = Path(bpy.path.abspath(self.directory))
        try:
            paths = export_maps(result_dir, out_dir, self.preset, size=self.size or None, bits=self.bits,
                                file_format=self.file_format, name=self.name or None, overwrite=self.overwrite)
        except (BlenderMatchError, OSError) as exc:
            self.report({'ERROR'}, str(exc))
            return {'CANCELLED'}
        self.report({'INFO'}, f"Exported {len(paths)} {self.preset} map(s) to {out_dir}: "
                              + ", ".join(p.name for p in paths))
        return {'FINISHED'}
