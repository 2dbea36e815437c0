"""``bpy.ops.blender_match.reset_parameters``: the sliders back to the material's stored values
(also fills them for a matched material that has none, e.g. one built by a script)."""

import bpy

from ..blender import addon, parameters


class BLENDER_MATCH_OT_reset_parameters(bpy.types.Operator):
    """Set the parameter sliders back to the active material's fitted values"""

    bl_idname = "blender_match.reset_parameters"
    bl_label = "Reset Parameters"
    bl_options = {'UNDO'}

    @classmethod
    def poll(cls, context):
        return parameters.stored_record(addon.active_material(context)) is not None

    def execute(self, context):
        material = addon.active_material(context)
        count = parameters.populate(material)
        self.report({'INFO'}, f"{count} parameter(s) of \"{material.name}\" reset to the fitted values")
        return {'FINISHED'}
