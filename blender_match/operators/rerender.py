"""``bpy.ops.blender_match.rerender``: the active material again, at another size.

Re-renders the material's stored parameters (its ``"blender_match"`` property: no photo needed)
in a worker into a new folder, builds a NEW material from it and puts it in the slot of the old
one, which stays in the file with its images, untouched::

    bpy.ops.blender_match.rerender(size='4K', wait=True)
"""

import bpy
from bpy.props import BoolProperty, EnumProperty

from ..blender import addon, match_job, parameters
from ._job_runner import JobRunner


def matched_material_poll(cls, context) -> bool:
    """The active material was made by a match and no job runs (for the poll of the operators
    that act on it)."""
    scene = getattr(context, "scene", None)
    if scene is None:
        return False
    material = addon.active_material(context)
    if parameters.stored_record(material) is None:
        cls.poll_message_set("The active material was not made by Blender Match")
        return False
    if match_job.running_job(scene) is not None:
        cls.poll_message_set("A job is running: wait for it or cancel it")
        return False
    return True


class BLENDER_MATCH_OT_rerender(JobRunner, bpy.types.Operator):
    """Render the active matched material's parameters again at another size, as a new material in its slot"""

    bl_idname = "blender_match.rerender"
    bl_label = "Re-render"
    bl_options = {'UNDO'}

    size: EnumProperty(name="Size", items=addon.SIZE_ITEMS, default="4K", options={'SKIP_SAVE'})
    device: EnumProperty(name="Device", items=[addon.PREFERENCES_DEVICE, *addon.DEVICE_ITEMS], default="default",
                         options={'SKIP_SAVE'})
    wait: BoolProperty(name="Wait", default=False, options={'HIDDEN', 'SKIP_SAVE'},
                       description="Run to the end before returning (scripts)")

    @classmethod
    def poll(cls, context):
        return matched_material_poll(cls, context)

    def execute(self, context):
        settings = getattr(context.scene, "blender_match", None)
        size = self.size if settings is None or self.properties.is_property_set("size") else settings.rerender_size
        device = self.device if settings is None or self.properties.is_property_set("device") else settings.device
        try:
            job = match_job.start_render(context, addon.active_material(context), addon.SIZES[size],
                                         device=device, pack=bool(settings and settings.pack))
        except match_job.JobError as exc:
            self.report({'ERROR'}, str(exc))
            return {'CANCELLED'}
        return self.run_job(context, job)
