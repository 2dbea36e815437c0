"""``bpy.ops.blender_match.cancel``: stop the scene's running match or re-render
(``target='SETUP'``: the backend setup)."""

import bpy
from bpy.props import EnumProperty

from ..blender import addon, match_job


def _running(context, target):
    if target == 'SETUP':
        job = match_job.SERVICES.get("setup")
        return job if job is not None and not job.done else None
    scene = getattr(context, "scene", None)
    return match_job.running_job(scene) if scene is not None else None


class BLENDER_MATCH_OT_cancel(bpy.types.Operator):
    """Stop the running job; nothing is changed"""

    bl_idname = "blender_match.cancel"
    bl_label = "Cancel"
    bl_options = {'INTERNAL'}

    target: EnumProperty(name="Job", items=[("JOB", "Match", "The scene's match or re-render"),
                                            ("SETUP", "Backend Setup", "The backend setup")],
                         default="JOB", options={'SKIP_SAVE'})

    @classmethod
    def poll(cls, context):
        return _running(context, 'JOB') is not None or _running(context, 'SETUP') is not None

    def execute(self, context):
        job = _running(context, self.target)
        if job is None:
            self.report({'WARNING'}, "Nothing is running")
            return {'CANCELLED'}
        job.cancel()
        addon.redraw_ui(context)
        self.report({'INFO'}, f"Cancelling the {job.kind}")
        return {'FINISHED'}
