"""``bpy.ops.blender_match.match_photo``: fit a procedural graph to a photo and put the new
material on the active object.

From the panel (``wait=False``) the match runs in a worker process while Blender stays usable: a
modal timer polls it, the panel shows the progress, Esc or Cancel stops it. From a script
(``wait=True``, or any call in ``blender --background``) it runs to the end before returning::

    bpy.ops.blender_match.match_photo(filepath="//photo.jpg", graph='AUTO', size=2048,
                                      quality='balanced', wait=True)

Properties left unset take the panel's settings (``scene.blender_match``). A failure raises
RuntimeError from a script (Blender's way for an operator's error report) and changes nothing.
"""

import bpy
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, StringProperty

from ..blender import addon, match_job
from ..vocabulary import DEFAULT_QUALITY
from ._job_runner import JobRunner

_SKIP = {'SKIP_SAVE'}


class BLENDER_MATCH_OT_match_photo(JobRunner, bpy.types.Operator):
    """Fit the chosen procedural graph to the photo and put the new material on the active object"""

    bl_idname = "blender_match.match_photo"
    bl_label = "Match Photo"
    bl_options = {'UNDO'}

    filepath: StringProperty(name="Photo", subtype='FILE_PATH', options=_SKIP,
                             description="Photo file of a flat material sample (flash on)")
    image: StringProperty(name="Image", options=_SKIP,
                          description="Name of an image in this file to use as the photo, instead of a file")
    graph: StringProperty(name="Graph", default="AUTO", options=_SKIP,
                          description="'AUTO' (automatic selection) or a library graph's name")
    size: IntProperty(name="Size", default=2048, min=16, max=8192, options=_SKIP,
                      description="Size of the maps written (a power of two)")
    quality: EnumProperty(name="Quality", items=addon.QUALITY_ITEMS, default=DEFAULT_QUALITY, options=_SKIP)
    device: EnumProperty(name="Device", items=[addon.PREFERENCES_DEVICE, *addon.DEVICE_ITEMS], default="default",
                         options=_SKIP)
    seed: IntProperty(name="Seed", default=0, min=0, options=_SKIP, description="The graph's random seed")
    pack: BoolProperty(name="Pack Images", default=False, options=_SKIP,
                       description="Pack the maps into the .blend (always done while it is unsaved)")
    calibrate: BoolProperty(name="Match Photo Colour", default=True, options=_SKIP,
                            description="Scale the base colour to the photo's exposure and white balance, before and "
                                        "after the fit (off: the graph's own colours)")
    match_scale: BoolProperty(name="Match Photo Scale", default=False, options=_SKIP,
                              description="Search the texture's scale in the photo, carried by the material's "
                                          "Mapping node (off: the graph's own scale)")
    tiling: FloatProperty(name="Tiling", default=1.0, min=0.001, options=_SKIP,
                          description="Repeats of the texture per UV unit")
    iterations: IntProperty(name="Iterations", default=0, min=0, options={'HIDDEN', 'SKIP_SAVE'},
                            description="Override the quality preset's iteration count (0: the preset's)")
    wait: BoolProperty(name="Wait", default=False, options={'HIDDEN', 'SKIP_SAVE'},
                       description="Run to the end before returning (scripts)")
    alternatives: StringProperty(name="Alternatives", options={'HIDDEN', 'SKIP_SAVE'},
                                 description="Graphs an earlier automatic match of this photo ranked near this one "
                                             "(comma-separated): the new material offers them in turn")

    @classmethod
    def poll(cls, context):
        if getattr(context, "scene", None) is None:
            return False
        if match_job.running_job(context.scene) is not None:
            cls.poll_message_set("A job is running: wait for it or cancel it")
            return False
        return True

    def _options(self, context) -> dict:
        """The operator's properties, the unset ones from the panel's settings (when the scene
        has them)."""
        settings = getattr(context.scene, "blender_match", None)
        options = self._photo(settings)
        options.update(self._fit_options(settings))
        options["seed"], options["iterations"] = self.seed, self.iterations
        options["alternatives"] = self.alternatives.split(",")  # start_match drops blanks and the graph
        return options

    def _photo(self, settings) -> dict:
        """``{"image": datablock}`` or ``{"photo": path}``: the operator's image or file when
        given, else the panel's photo."""
        if self.image:
            image = bpy.data.images.get(self.image)
            if image is None:
                raise match_job.JobError(f"no image named {self.image!r} in this file")
            return {"image": image}
        if settings is None or self.properties.is_property_set("filepath"):
            return {"photo": self.filepath}
        if settings.photo_source == 'IMAGE':
            if settings.photo_image is None:
                raise match_job.JobError("no photo image chosen")
            return {"image": settings.photo_image}
        return {"photo": settings.photo_path}

    def _fit_options(self, settings) -> dict:
        """Graph, size, quality, device, colour and scale matching, packing and tiling: the operator's when
        set, else the panel's (whose size is a "1K"/"2K"/"4K" choice)."""
        names = ("graph", "size", "quality", "device", "calibrate", "match_scale", "pack", "tiling")
        options = {name: getattr(self, name) for name in names}
        if settings is None:
            return options
        for name in names:
            if not self.properties.is_property_set(name):
                options[name] = addon.SIZES[settings.size] if name == "size" else getattr(settings, name)
        return options

    def execute(self, context):
        try:
            job = match_job.start_match(context, **self._options(context))
        except match_job.JobError as exc:
            self.report({'ERROR'}, str(exc))
            return {'CANCELLED'}
        for note in job.notes:
            self.report({'INFO'}, note[0].upper() + note[1:])
        return self.run_job(context, job)
