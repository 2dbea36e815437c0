"""``bpy.ops.blender_match.probe_worker``: start the worker once and report its Python, torch
and the devices it can use (the preferences' "Test worker" button)."""

import bpy
from bpy.props import BoolProperty

from ..blender import match_job
from ._job_runner import JobRunner


class BLENDER_MATCH_OT_probe_worker(JobRunner, bpy.types.Operator):
    """Start the worker once and show its Python, torch version and devices"""

    bl_idname = "blender_match.probe_worker"
    bl_label = "Test Worker"

    escape_cancels = False

    wait: BoolProperty(name="Wait", default=False, options={'HIDDEN', 'SKIP_SAVE'},
                       description="Run to the end before returning (scripts)")

    @classmethod
    def poll(cls, context):
        job = match_job.SERVICES.get("probe")
        return job is None or job.done

    def execute(self, context):
        try:
            job = match_job.start_probe(context)
        except match_job.JobError as exc:
            self.report({'ERROR'}, str(exc))
            return {'CANCELLED'}
        return self.run_job(context, job)
