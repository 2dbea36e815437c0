"""bpy-side helpers of the add-on (imported only inside Blender)."""
