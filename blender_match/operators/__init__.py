"""Blender operators (``bpy.ops.blender_match.*``), one per module; ``classes`` lists them for
registration. ``_job_runner`` holds what the job operators share (synchronous or modal polling of
a ``blender.match_job`` controller). Modules defining bpy classes do not use ``from __future__
import annotations``: Blender registers the property annotations (``name: StringProperty(...)``),
which must stay the property objects themselves, not strings."""

from .apply_parameters import BLENDER_MATCH_OT_apply_parameters
from .cancel import BLENDER_MATCH_OT_cancel
from .export_maps import BLENDER_MATCH_OT_export_maps
from .match_photo import BLENDER_MATCH_OT_match_photo
from .probe_worker import BLENDER_MATCH_OT_probe_worker
from .rerender import BLENDER_MATCH_OT_rerender
from .reset_parameters import BLENDER_MATCH_OT_reset_parameters
from .setup_backend import BLENDER_MATCH_OT_setup_backend

classes: tuple = (
    BLENDER_MATCH_OT_match_photo,
    BLENDER_MATCH_OT_cancel,
    BLENDER_MATCH_OT_rerender,
    BLENDER_MATCH_OT_apply_parameters,
    BLENDER_MATCH_OT_reset_parameters,
    BLENDER_MATCH_OT_export_maps,
    BLENDER_MATCH_OT_setup_backend,
    BLENDER_MATCH_OT_probe_worker,
)
