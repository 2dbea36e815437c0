"""Blender operators (``bpy.ops.blender_match.*``), one per module. ``classes`` lists them for
registration; the add-on's operators arrive with the add-on issue."""

classes: tuple = ()
