"""The add-on's settings: ``scene.blender_match`` (what the Match panel edits) and
``material.blender_match_params`` (the matched material's exposed-parameter sliders).

The runtime state of a job (progress, stage, time left, last result or error) is not stored
here: it lives in ``match_job``'s registry, written only on the main thread.
"""

import bpy
from bpy.props import (
    BoolProperty,
    CollectionProperty,
    EnumProperty,
    FloatProperty,
    FloatVectorProperty,
    PointerProperty,
    StringProperty,
)

from ..vocabulary import DEFAULT_QUALITY
from . import addon

_GRAPH_ITEMS: list = []  # Blender needs the enum items of a callback kept alive


_FAMILY_ITEMS: list = []


def family_items(self, context):
    _FAMILY_ITEMS[:] = addon.family_items()
    return _FAMILY_ITEMS


def graph_items(self, context):
    """'AUTO' then the library graphs of the chosen family, with their thumbnails. A graph keeps
    its number (its place in the whole library) whatever the family shown, since Blender stores a
    dynamic enum's choice as that number."""
    family = getattr(self, "graph_family", addon.ALL_FAMILIES)
    items = [("AUTO", "Automatic", "Pick the library graph that fits the photo best", "AUTO", 0)]
    for number, (name, entry) in enumerate(addon.library_graphs().items(), start=1):
        if family in (addon.ALL_FAMILIES, entry["family"]):
            items.append((name, addon.graph_title(name), entry.get("description") or name,
                          addon.graph_icon(name), number))
    _GRAPH_ITEMS[:] = items
    return _GRAPH_ITEMS


def family_changed(self, context):
    """A graph outside the family now shown goes back to Automatic (the menu could not show it)."""
    if self.graph != "AUTO" and self.graph not in {item[0] for item in graph_items(self, context)}:
        self.graph = "AUTO"


class BLENDER_MATCH_PG_settings(bpy.types.PropertyGroup):
    """What the Match panel sets for the next match, exports and re-renders."""

    photo_source: EnumProperty(
        name="Photo", items=[("FILE", "File", "A photo file on disk"),
                             ("IMAGE", "Image", "An image already in this file")], default="FILE")
    photo_path: StringProperty(name="Photo File", subtype="FILE_PATH",
                               description="Photo of a flat material sample, taken with the flash on")
    photo_image: PointerProperty(name="Photo Image", type=bpy.types.Image,
                                 description="An image of this file to use as the photo")
    graph_family: EnumProperty(name="Family", items=family_items, update=family_changed,
                               description="Which family of library graphs the graph menu shows")
    graph: EnumProperty(name="Graph", items=graph_items,
                        description="The procedural graph to fit (Automatic: pick the best)")
    quality: EnumProperty(name="Quality", items=addon.QUALITY_ITEMS, default=DEFAULT_QUALITY)
    size: EnumProperty(name="Size", items=addon.SIZE_ITEMS, default="2K",
                       description="Size of the texture maps written")
    device: EnumProperty(name="Device", items=[addon.PREFERENCES_DEVICE, *addon.DEVICE_ITEMS], default="default")
    pack: BoolProperty(name="Pack Images", default=False,
                       description="Pack the maps into the .blend (always done while it is unsaved)")
    calibrate: BoolProperty(name="Match Photo Colour", default=True,
                            description="Scale the base colour to the photo's exposure and white balance, before and "
                                        "after the fit (off: the graph's own colours)")
    match_scale: BoolProperty(name="Match Photo Scale", default=False,
                              description="Search the texture's scale in the photo, carried by the material's "
                                          "Mapping node (off: the graph's own scale)")
    tiling: FloatProperty(name="Tiling", default=1.0, min=0.001, soft_min=0.1, soft_max=16.0,
                          description="Repeats of the texture per UV unit")
    rerender_size: EnumProperty(name="Re-render Size", items=addon.SIZE_ITEMS, default="4K")
    export_preset: EnumProperty(name="Preset", items=[("gltf", "glTF", "glTF 2.0 metallic-roughness"),
                                                      ("unreal", "Unreal", "Unreal Engine (ORM, DirectX normal)"),
                                                      ("unity", "Unity", "Unity URP/HDRP Lit")], default="gltf")
    export_size: EnumProperty(name="Export Size",
                              items=[("SAME", "Same", "The maps' own size"), *addon.SIZE_ITEMS], default="SAME")
    export_format: EnumProperty(name="Format", items=[("PNG", "PNG", "PNG images"),
                                                      ("OPEN_EXR", "OpenEXR", "OpenEXR images (linear)")],
                                default="PNG")
    export_high_depth: BoolProperty(name="High Bit Depth", default=False,
                                    description="16-bit PNG or 32-bit float OpenEXR (else 8-bit PNG, half EXR)")


def _get_value(self):
    return min(max(self.raw, self.minimum), self.maximum)


def _set_value(self, value):
    self.raw = min(max(value, self.minimum), self.maximum)


class BLENDER_MATCH_PG_parameter(bpy.types.PropertyGroup):
    """One exposed parameter of a matched material (``name`` is the parameter's)."""

    kind: EnumProperty(items=[("FLOAT", "Float", ""), ("COLOR", "Color", "")], default="FLOAT")
    minimum: FloatProperty(default=0.0)
    maximum: FloatProperty(default=1.0)
    raw: FloatProperty(default=0.0)
    # The same value, clamped to [minimum, maximum]: drawn as a slider when the range lies in
    # [0, 1] (``value``), as a number field with a wider soft range otherwise (``value_wide``).
    value: FloatProperty(name="Value", get=_get_value, set=_set_value, min=-1e6, max=1e6, soft_min=0.0,
                         soft_max=1.0, precision=3)
    value_wide: FloatProperty(name="Value", get=_get_value, set=_set_value, min=-1e6, max=1e6, soft_min=0.0,
                              soft_max=8.0, precision=3, step=1)
    color: FloatVectorProperty(name="Color", subtype="COLOR_GAMMA", size=3, min=0.0, max=1.0, default=(0.5, 0.5, 0.5))

    @property
    def title(self) -> str:
        return addon.graph_title(self.name)

    @property
    def unit_range(self) -> bool:
        return self.minimum >= 0.0 and self.maximum <= 1.0


classes = (BLENDER_MATCH_PG_settings, BLENDER_MATCH_PG_parameter)


def register():
    bpy.types.Scene.blender_match = PointerProperty(type=BLENDER_MATCH_PG_settings)
    bpy.types.Material.blender_match_params = CollectionProperty(type=BLENDER_MATCH_PG_parameter)


def unregister():
    for owner, name in ((bpy.types.Material, "blender_match_params"), (bpy.types.Scene, "blender_match")):
        if hasattr(owner, name):
            delattr(owner, name)
    _GRAPH_ITEMS.clear()
    addon.release_previews()
