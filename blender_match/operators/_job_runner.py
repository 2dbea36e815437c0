"""What the add-on's job operators share: run a ``match_job`` controller either synchronously
(``wait=True``, or Blender in the background, where modal timers never fire) or modally, polled
by a 0.1 s window-manager timer on the main thread while Blender stays responsive; Esc cancels.
"""

import bpy

from ..blender import addon, match_job


class JobRunner:
    """Mixin for an Operator whose ``execute`` starts a job and returns ``self.run_job(...)``."""

    escape_cancels = True

    def run_job(self, context, job):
        if getattr(self, "wait", False) or bpy.app.background or context.window is None:
            job.wait()
            return self.finish_job(context, job)
        self._job = job
        self._timer_key = f"{self.bl_idname}:{id(self)}"
        match_job.add_timer(self._timer_key, context.window_manager, context.window)
        context.window_manager.modal_handler_add(self)
        addon.redraw_ui(context)
        return {'RUNNING_MODAL'}

    def modal(self, context, event):
        job = self._job
        if event.type == 'TIMER':
            try:
                job.poll()
            except Exception as exc:  # noqa: BLE001 - never leave a timer or a worker behind
                job.kill()
                match_job.remove_timer(self._timer_key)
                self.report({'ERROR'}, f"{type(exc).__name__}: {exc}")
                return {'CANCELLED'}
            addon.redraw_ui(context)
            if job.done:
                match_job.remove_timer(self._timer_key)
                return self.finish_job(context, job)
            return {'PASS_THROUGH'}  # other modal operators need their timer events too
        if event.type == 'ESC' and event.value == 'PRESS' and self.escape_cancels:
            job.cancel()
            addon.redraw_ui(context)
            return {'RUNNING_MODAL'}
        return {'PASS_THROUGH'}

    def cancel(self, context):
        """Blender removes the handler (a file is loaded, the window closes): stop the job."""
        job = getattr(self, "_job", None)
        if job is not None and not job.done:
            job.kill()
        match_job.remove_timer(getattr(self, "_timer_key", None))

    def finish_job(self, context, job):
        addon.redraw_ui(context)
        if job.state == "finished":
            self.report({'INFO'}, job.message)
            return {'FINISHED'}
        if job.state == "cancelled":
            self.report({'WARNING'}, job.message)
            return {'CANCELLED'}
        self.report({'ERROR'}, job.message)
        return {'CANCELLED'}
