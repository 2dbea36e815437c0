"""``bpy.ops.blender_match.setup_backend``: create the worker's Python (the backend).

A virtual environment in the extension's user folder, made from Blender's own Python, with torch
and the engine's other packages from PyPI (``worker.backend_setup.BackendSetup``). It runs in the
background; a modal timer polls it and the add-on's preferences show its progress. Once it is
done, matches use it unless the preferences name another worker Python.
"""

import shlex
import sys

import bpy
from bpy.props import BoolProperty, StringProperty

from ..blender import addon, match_job
from ._job_runner import JobRunner


class BLENDER_MATCH_OT_setup_backend(JobRunner, bpy.types.Operator):
    """Download and install the matching backend (PyTorch and the engine's packages) into the add-on's folder"""

    bl_idname = "blender_match.setup_backend"
    bl_label = "Set Up Backend"

    escape_cancels = False  # the preferences' Cancel button stops it, not any Esc anywhere

    base_python: StringProperty(name="Base Python", subtype='FILE_PATH', options={'SKIP_SAVE'},
                                description="Python to create the environment with (default: Blender's own)")
    pip_arguments: StringProperty(name="pip Arguments", options={'SKIP_SAVE'},
                                  description="Extra pip arguments, e.g. --index-url for another torch build "
                                              "(default: the preferences')")
    wait: BoolProperty(name="Wait", default=False, options={'HIDDEN', 'SKIP_SAVE'},
                       description="Run to the end before returning (scripts)")

    @classmethod
    def poll(cls, context):
        job = match_job.SERVICES.get("setup")
        if job is not None and not job.done:
            cls.poll_message_set("The backend setup is running")
            return False
        return True

    def execute(self, context):
        prefs = addon.preferences(context)
        args = self.pip_arguments if self.properties.is_property_set("pip_arguments") else (
            prefs.pip_arguments if prefs is not None else "")
        try:
            job = match_job.start_setup(bpy.path.abspath(self.base_python) if self.base_python else sys.executable,
                                        shlex.split(args))
        except (match_job.JobError, ValueError) as exc:
            self.report({'ERROR'}, str(exc))
            return {'CANCELLED'}
        self.report({'INFO'}, f"Setting up the backend in {job.target_dir}")
        return self.run_job(context, job)
