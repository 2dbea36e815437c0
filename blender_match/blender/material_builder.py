"""Turn a match result folder into a Blender material, and put it on an object.

A result folder (written by the matching pipeline) holds the maps as PNGs and a ``report.json``
whose ``"maps"`` says, per usage, the file and whether the map is *flat* (every pixel the same;
its value is given). ``build_material`` makes a NEW material every time — it never reuses or
changes an existing material or image, so rebuilding cannot destroy a user's edits:

    Texture Coordinate (UV) -> Mapping (Scale = tiling x zoom) -> Image Texture per non-flat map
        base colour (sRGB)             -> Principled "Base Color"
        roughness, metallic (Non-Color) -> Principled "Roughness", "Metallic"
        normal (Non-Color, OpenGL = Blender's convention) -> Normal Map (tangent) -> "Normal"
        height (Non-Color) -> Displacement (scale BUMP_SCALE) -> Material Output "Displacement"
        anisotropy level (Non-Color) -> Principled "Anisotropic"
        anisotropy angle (Non-Color) -> Add a quarter turn -> Principled "Anisotropic Rotation"
    Tangent (UV map) -> Principled "Tangent", when the material is anisotropic
    Principled BSDF -> Material Output

The zoom is the fit's (params.json's "calibration.zoom": texture periods across the photo), so a
UV square shows the material at the photo's scale with the maps one seamless period; ``tiling``
is the user's repeat on top of it.

A flat map becomes the socket's default value instead of a texture (a flat normal or height map
adds nothing). Height drives the Displacement output with ``displacement_method`` 'BUMP': bump
works on any mesh in EEVEE and Cycles, whereas true displacement needs a finely subdivided mesh
and Cycles; users who have one switch the method themselves. Ambient occlusion is left out: the
Principled BSDF has no input for it and renderers compute their own.

Anisotropy (brushed metals): the angle map is the direction of the brushing, while Blender's
"Anisotropic Rotation" turns the direction the highlight stretches along, across the brushing, so
a quarter turn (``vocabulary.ANISOTROPY_TANGENT_TURN``) is added. The Principled BSDF ignores both
unless its "Tangent" input is linked: a Tangent node of the UV map's u direction (its map left
empty, so it is the same active render UV map the Texture Coordinate node gives the images)
makes the rotation relative to the texture's +u. The Mapping node only scales, uniformly, so it
turns nothing. Without the level map, or with a flat level of 0, neither the tangent nor the angle
image is added.

What re-rendering needs without the photo (graph, fitted parameters as JSON text, size, loss,
folder) is stored on the material as the ``"blender_match"`` custom property, with what the match
came from when the caller gives it (``origin``: the photo file or image datablock, the quality)
and, for an automatic match, the graphs its ranking put next after the kept one
(``"alternatives"``): the ranking's near-ties, which the panel offers to match instead.

bpy is imported inside the functions, so this module imports without Blender; ``read_report``
and ``srgb_to_linear`` are shared with ``export_presets``.
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from ..colour import SRGB_GAMMA, SRGB_KNEE, SRGB_OFFSET, SRGB_SCALE, SRGB_SLOPE
from ..errors import ResultFolderError
from ..vocabulary import (
    ANISOTROPY,
    ANISOTROPY_ANGLE,
    ANISOTROPY_TANGENT_TURN,
    CALIBRATION,
    OUTPUTS,
    PARAMS_FILE,
    REPORT_FILE,
    ZOOM,
    ranked_alternatives,
)

PROPERTY = "blender_match"
# What a match came from, which a re-rendered material carries on: the photo (a file path, or an
# image datablock's name), the quality, the ranking's alternatives
MATCH_ORIGIN = ("photo", "photo_image", "quality", "alternatives")
BUMP_SCALE = 0.02  # metres of relief for the full 0..1 height range: a subtle bump, not a cliff

# usage -> (node label, colour space, Principled input it feeds directly or None), in the order
# the image nodes are stacked top to bottom.
IMAGE_MAPS = {usage: (OUTPUTS[usage].label, OUTPUTS[usage].colour_space, principled)
              for usage, principled in (("basecolor", "Base Color"), ("roughness", "Roughness"),
                                        ("metallic", "Metallic"), ("normal", None), ("height", None),
                                        (ANISOTROPY, "Anisotropic"), (ANISOTROPY_ANGLE, None))}

# Node columns, left to right (x in node-editor units), and the vertical step between images.
_X = {"coords": -1500, "mapping": -1300, "images": -1000, "converters": -650, "shader": -400,
      "output": 0}
_ROW = -300


def srgb_to_linear(values):
    """sRGB-encoded values in [0, 1] -> linear (IEC 61966-2-1). Blender's colour sockets and
    OpenEXR files hold linear colour, while the base-colour PNG holds sRGB-encoded values. The
    curve is ``blender_match.colour``'s, which the engine's renderer applies to tensors."""
    v = np.clip(np.asarray(values, dtype=np.float32), 0.0, 1.0)
    curve = ((v + SRGB_OFFSET) / SRGB_SCALE) ** SRGB_GAMMA
    return np.where(v <= SRGB_KNEE, v / SRGB_SLOPE, curve).astype(np.float32)


def read_report(result_dir) -> dict:
    """The folder's report.json as a dict with a ``"maps"`` object."""
    path = Path(result_dir) / REPORT_FILE
    if not path.is_file():
        raise ResultFolderError(f"{result_dir}: no {REPORT_FILE} (not a blender_match result folder)")
    try:
        report = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise ResultFolderError(f"{path}: unreadable ({exc})") from None
    if not isinstance(report, dict) or not isinstance(report.get("maps"), dict):
        raise ResultFolderError(f'{path}: no "maps" object')
    return report


def map_path(result_dir, report: dict, usage: str) -> Path:
    """The existing file of map ``usage`` listed in the report."""
    entry = report["maps"].get(usage)
    file = entry.get("file") if isinstance(entry, dict) else None
    if not isinstance(file, str):
        raise ResultFolderError(f'{Path(result_dir) / REPORT_FILE}: no file for map "{usage}"')
    path = Path(result_dir) / file
    if not path.is_file():
        raise ResultFolderError(f"{path}: missing (listed in {REPORT_FILE})")
    return path


def graph_name(report: dict, result_dir) -> str:
    """The fitted graph's name ("marble"; a .sbs path gives its stem), else the folder's name."""
    graph = report.get("graph")
    if isinstance(graph, str) and graph:
        name = Path(graph).name
        return name[:-4] if name.lower().endswith(".sbs") else name
    return Path(result_dir).resolve().name


def build_material(result_dir, name=None, pack=False, tiling=1.0, origin: dict | None = None):
    """A new material built from the result folder (see the module docstring); returns it.

    ``name`` defaults to "Match <graph>" (Blender suffixes duplicates); images are named
    "<name> <usage>". ``pack`` packs the images into the .blend. ``tiling`` repeats the photo's
    framing (the fit's zoom) that many times per UV unit. ``origin``: what the match came from
    (``MATCH_ORIGIN`` keys), kept in the custom property. Everything is checked before any
    datablock is created.
    """
    import bpy  # here, not at the top: read_report and srgb_to_linear serve without Blender

    if not tiling > 0:
        raise ValueError(f"tiling must be positive, not {tiling}")
    result_dir = Path(result_dir).resolve()
    report = read_report(result_dir)
    params, params_data = _read_params(result_dir)
    maps = report["maps"]
    flat = {u: maps[u]["flat"] for u in IMAGE_MAPS
            if isinstance(maps.get(u), dict) and maps[u].get("flat") is not None}
    files = {u: map_path(result_dir, report, u) for u in IMAGE_MAPS if u in maps and u not in flat}
    anisotropic = ANISOTROPY in files or flat.get(ANISOTROPY, [0.0])[0] > 0
    if not anisotropic:  # the angle turns nothing
        files.pop(ANISOTROPY_ANGLE, None)
    base_name = name or f"Match {graph_name(report, result_dir)}"

    material = bpy.data.materials.new(base_name)
    if material.node_tree is None:  # Blender < 5.0 creates the node tree only on request
        material.use_nodes = True
    material.displacement_method = "BUMP"
    tree = material.node_tree
    tree.nodes.clear()
    output = _node(tree, "ShaderNodeOutputMaterial", "Material Output", _X["output"], 0)
    shader = _node(tree, "ShaderNodeBsdfPrincipled", "Principled BSDF", _X["shader"], 0)
    tree.links.new(shader.outputs["BSDF"], output.inputs["Surface"])
    _set_flat_values(shader, flat)
    if files:
        vector = _mapping(tree, tiling * fitted_zoom(params_data), y=_ROW * (len(files) - 1) / 2)
        for row, (usage, path) in enumerate(files.items()):
            image = _load_image(bpy, path, f"{base_name} {usage}", IMAGE_MAPS[usage][1], pack)
            color = _image_node(tree, usage, image, vector, y=_ROW * row)
            _wire(tree, usage, color, shader, output, y=_ROW * row)
    if anisotropic:
        tangent = _node(tree, "ShaderNodeTangent", "Tangent", _X["converters"], _ROW * len(files))
        tangent.direction_type = "UV_MAP"
        tree.links.new(tangent.outputs["Tangent"], shader.inputs["Tangent"])
    material[PROPERTY] = _record(report, params, result_dir, origin)
    return material


def fitted_zoom(params: dict) -> float:
    """The fit's zoom in a parsed params.json (1 when absent, as in results written before it)."""
    value = params.get("params", {}).get(f"{CALIBRATION}.{ZOOM}", 1.0) if isinstance(params, dict) else 1.0
    return float(value) if isinstance(value, (int, float)) and value > 0 else 1.0


def assign_material(obj, material) -> bool:
    """Put ``material`` in ``obj``'s active material slot (the slot's previous material stays in
    the file), or in a new slot when it has none. Returns False, assigning nothing, for objects
    that cannot hold materials (empties, cameras, lights)."""
    if obj is None or not hasattr(obj.data, "materials"):
        return False
    if obj.material_slots:
        obj.material_slots[obj.active_material_index].material = material
    else:
        obj.data.materials.append(material)
    return True


def _read_params(result_dir: Path) -> tuple[str, dict]:
    """params.json's text, the fitted parameters that re-rendering needs, and its parsed content."""
    path = result_dir / PARAMS_FILE
    try:
        text = path.read_text(encoding="utf-8")
        data = json.loads(text)
    except FileNotFoundError:
        raise ResultFolderError(f"{path}: missing (the fitted parameters)") from None
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise ResultFolderError(f"{path}: unreadable ({exc})") from None
    return text, data


def _record(report: dict, params: str, result_dir: Path, origin: dict | None = None) -> dict:
    """The custom property's value: the report's, with the ``MATCH_ORIGIN`` entries of ``origin``
    (the report's own ranking, an automatic match's, comes before the origin's alternatives);
    None and empty lists (which an IDProperty cannot hold, or need not) are left out."""
    record = {key: (origin or {}).get(key) for key in MATCH_ORIGIN}
    record.update({"graph": report.get("graph"), "params": params, "size": report.get("size"),
                   "loss": report.get("loss_final"), "result_dir": str(result_dir)})
    record["alternatives"] = ranked_alternatives(report) or record["alternatives"]
    return {key: value for key, value in record.items() if value is not None and value != []}


def _node(tree, kind: str, label: str, x: float, y: float):
    node = tree.nodes.new(kind)
    node.name = node.label = label
    node.location = (x, y)
    return node


def _mapping(tree, scale: float, y: float):
    """UV coordinates scaled by ``scale``: the Vector every image node reads."""
    coords = _node(tree, "ShaderNodeTexCoord", "Texture Coordinate", _X["coords"], y)
    mapping = _node(tree, "ShaderNodeMapping", "Tiling", _X["mapping"], y)
    mapping.inputs["Scale"].default_value = (scale, scale, 1.0)
    tree.links.new(coords.outputs["UV"], mapping.inputs["Vector"])
    return mapping.outputs["Vector"]


def _load_image(bpy, path: Path, name: str, colorspace: str, pack: bool):
    """A new image datablock for ``path`` (never an existing one, which the user may have edited)."""
    image = bpy.data.images.load(str(path), check_existing=False)
    image.name = name
    image.colorspace_settings.name = colorspace
    if pack:
        image.pack()
    return image


def _image_node(tree, usage: str, image, vector, y: float):
    node = _node(tree, "ShaderNodeTexImage", IMAGE_MAPS[usage][0], _X["images"], y)
    node.image = image
    tree.links.new(vector, node.inputs["Vector"])
    return node.outputs["Color"]


def _wire(tree, usage: str, color, shader, output, y: float):
    """Connect an image's Color output to where its map acts."""
    target = IMAGE_MAPS[usage][2]
    if target:
        tree.links.new(color, shader.inputs[target])
    elif usage == ANISOTROPY_ANGLE:
        turn = _node(tree, "ShaderNodeMath", "Anisotropic Rotation", _X["converters"], y)
        turn.operation = "ADD"
        turn.inputs[1].default_value = ANISOTROPY_TANGENT_TURN
        tree.links.new(color, turn.inputs[0])
        tree.links.new(turn.outputs["Value"], shader.inputs["Anisotropic Rotation"])
    elif usage == "normal":
        normal_map = _node(tree, "ShaderNodeNormalMap", "Normal Map", _X["converters"], y)
        normal_map.space = "TANGENT"
        tree.links.new(color, normal_map.inputs["Color"])
        tree.links.new(normal_map.outputs["Normal"], shader.inputs["Normal"])
    else:
        displacement = _node(tree, "ShaderNodeDisplacement", "Displacement", _X["converters"], y)
        displacement.inputs["Midlevel"].default_value = 0.5
        displacement.inputs["Scale"].default_value = BUMP_SCALE
        tree.links.new(color, displacement.inputs["Height"])
        tree.links.new(displacement.outputs["Displacement"], output.inputs["Displacement"])


def _set_flat_values(shader, flat: dict):
    """Flat maps as the Principled BSDF's default values (base colour converted to linear, the
    anisotropy angle turned a quarter)."""
    if "basecolor" in flat:
        rgb = list(flat["basecolor"])
        rgb = rgb * 3 if len(rgb) == 1 else rgb[:3]
        shader.inputs["Base Color"].default_value = (*(float(c) for c in srgb_to_linear(rgb)), 1.0)
    for usage in ("roughness", "metallic", ANISOTROPY):
        if usage in flat:
            shader.inputs[IMAGE_MAPS[usage][2]].default_value = float(flat[usage][0])
    if ANISOTROPY_ANGLE in flat:
        rotation = (float(flat[ANISOTROPY_ANGLE][0]) + ANISOTROPY_TANGENT_TURN) % 1.0
        shader.inputs["Anisotropic Rotation"].default_value = rotation
