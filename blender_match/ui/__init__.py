"""Blender UI (the "Match" N-panel and preferences), one panel per module. ``classes`` lists them
for registration; the panels arrive with the add-on issue."""

classes: tuple = ()
