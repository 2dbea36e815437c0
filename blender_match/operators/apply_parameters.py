"""``bpy.ops.blender_match.apply_parameters``: the paper's material editing.

The panel's sliders (``material.blender_match_params``) hold the active material's exposed
parameters; Apply writes the stored params.json with the sliders' values (same format) and
re-renders it, like ``rerender``, into a new folder and a NEW material put in the old one's slot::

    material.blender_match_params["roughness"].value = 0.9
    bpy.ops.blender_match.apply_parameters(wait=True)
"""

import bpy
from bpy.props import BoolProperty, EnumProperty

from ..blender import addon, match_job, parameters
from ._job_runner import JobRunner
from .rerender import matched_material_poll


class BLENDER_MATCH_OT_apply_parameters(JobRunner, bpy.types.Operator):
    """Render the active matched material with the edited parameters, as a new material in its slot"""

    bl_idname = "blender_match.apply_parameters"
    bl_label = "Apply"
    bl_options = {'UNDO'}

    size: EnumProperty(name="Size", items=[("SAME", "Same", "The material's own size"), *addon.SIZE_ITEMS],
                       default="SAME", options={'SKIP_SAVE'})
    wait: BoolProperty(name="Wait", default=False, options={'HIDDEN', 'SKIP_SAVE'},
                       description="Run to the end before returning (scripts)")

    @classmethod
    def poll(cls, context):
        if not matched_material_poll(cls, context):
            return False
        if not len(getattr(addon.active_material(context), parameters.COLLECTION, ())):
            cls.poll_message_set("The material has no editable parameters")
            return False
        return True

    def execute(self, context):
        material = addon.active_material(context)
        settings = getattr(context.scene, "blender_match", None)
        if self.size == "SAME":
            size = (parameters.stored_record(material) or {}).get("size")
            size = int(size) if isinstance(size, (int, float)) and size > 0 else 2048
        else:
            size = addon.SIZES[self.size]
        try:
            job = match_job.start_render(context, material, size, values=parameters.slider_values(material),
                                         device=settings.device if settings else "default",
                                         pack=bool(settings and settings.pack))
        except match_job.JobError as exc:
            self.report({'ERROR'}, str(exc))
            return {'CANCELLED'}
        return self.run_job(context, job)
