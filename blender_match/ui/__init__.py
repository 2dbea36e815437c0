"""Blender UI: the "Match" sidebar panel of the 3D Viewport and the Shader Editor (``panel``);
``classes`` lists them for registration. The preferences are in ``blender_match.preferences``."""

from .panel import BLENDER_MATCH_PT_shader_editor, BLENDER_MATCH_PT_view3d

classes: tuple = (BLENDER_MATCH_PT_view3d, BLENDER_MATCH_PT_shader_editor)
