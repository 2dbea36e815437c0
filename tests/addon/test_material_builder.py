"""The Blender material built from a result folder (real bpy, in-process)."""
from __future__ import annotations

import json

import pytest
import torch

from blender_match.image_files import write_png
from blender_match.vocabulary import (
    ANISOTROPY,
    ANISOTROPY_ANGLE,
    CALIBRATION,
    MATERIAL_OUTPUTS,
    USAGES,
    ZOOM,
    ranked_alternatives,
)

bpy = pytest.importorskip("bpy")

from blender_match.blender.material_builder import (  # noqa: E402  (after the bpy skip)
    BUMP_SCALE,
    ResultFolderError,
    assign_material,
    build_material,
    srgb_to_linear,
)

W, H = 8, 4
PARAMS = {"graph": "marble", "params": {"scale": [0.25, 4.0], "seed": 3}}


@pytest.fixture(autouse=True)
def _empty_blender():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    yield


def make_result(root, flat=None, ao=True, graph="marble", params=PARAMS, anisotropy=False, ranking=None):
    """A result folder as the pipeline writes it; ``flat`` maps usage -> constant value; the
    anisotropy maps only with ``anisotropy`` (a brushed metal's); ``ranking`` (graph names, best
    first) as an automatic match reports it."""
    flat = flat or {}
    root.mkdir(parents=True, exist_ok=True)
    maps = {}
    for usage, file, channels, bits in ((o.name, o.file, o.file_channels, o.bits) for o in MATERIAL_OUTPUTS):
        if (usage == "ambientocclusion" and not ao) or (usage in (ANISOTROPY, ANISOTROPY_ANGLE) and not anisotropy):
            continue
        if usage in flat:
            img = torch.full((1, channels, H, W), flat[usage])
        else:
            img = torch.rand(1, channels, H, W)
        write_png(root / file, img, bits=bits)
        maps[usage] = {"file": file, "flat": [flat[usage]] * channels if usage in flat else None}
    (root / "params.json").write_text(json.dumps(params))
    report = {"graph": graph, "loss_final": 0.125, "seconds": 3.5, "size": W, "maps": maps}
    if ranking is not None:
        report["ranking"] = [{"graph": name, "distance": 0.01 * (i + 1), "start": "bank", "gain": [1.0, 1.0, 1.0]}
                             for i, name in enumerate(ranking)]
    (root / "report.json").write_text(json.dumps(report))
    return root


def linked(tree, from_node, from_socket, to_node, to_socket):
    return any(link.from_node.name == from_node and link.from_socket.identifier == from_socket
               and link.to_node.name == to_node and link.to_socket.identifier == to_socket
               for link in tree.links)


def node_types(tree):
    return sorted(node.bl_idname for node in tree.nodes)


def test_nodes_links_and_colour_spaces(tmp_path):
    material = build_material(make_result(tmp_path / "r"))
    tree = material.node_tree
    assert material.name == "Match marble"
    assert node_types(tree) == sorted(
        ["ShaderNodeOutputMaterial", "ShaderNodeBsdfPrincipled", "ShaderNodeTexCoord", "ShaderNodeMapping",
         "ShaderNodeNormalMap", "ShaderNodeDisplacement"] + ["ShaderNodeTexImage"] * 5)
    assert linked(tree, "Principled BSDF", "BSDF", "Material Output", "Surface")
    assert linked(tree, "Base Color", "Color", "Principled BSDF", "Base Color")
    assert linked(tree, "Roughness", "Color", "Principled BSDF", "Roughness")
    assert linked(tree, "Metallic", "Color", "Principled BSDF", "Metallic")
    assert linked(tree, "Normal", "Color", "Normal Map", "Color")
    assert linked(tree, "Normal Map", "Normal", "Principled BSDF", "Normal")
    assert linked(tree, "Height", "Color", "Displacement", "Height")
    assert linked(tree, "Displacement", "Displacement", "Material Output", "Displacement")
    assert tree.nodes["Normal Map"].space == "TANGENT"
    assert tree.nodes["Displacement"].inputs["Scale"].default_value == pytest.approx(BUMP_SCALE)
    assert material.displacement_method == "BUMP"
    spaces = {n.name: n.image.colorspace_settings.name for n in tree.nodes if n.bl_idname == "ShaderNodeTexImage"}
    assert spaces == {"Base Color": "sRGB", "Roughness": "Non-Color", "Metallic": "Non-Color",
                      "Normal": "Non-Color", "Height": "Non-Color"}
    assert all(node.label for node in tree.nodes)


def test_layout_is_in_columns_left_to_right(tmp_path):
    tree = build_material(make_result(tmp_path / "r")).node_tree
    x = {node.name: node.location.x for node in tree.nodes}
    assert (x["Texture Coordinate"] < x["Tiling"] < x["Base Color"] < x["Normal Map"]
            < x["Principled BSDF"] < x["Material Output"])
    images = [n for n in tree.nodes if n.bl_idname == "ShaderNodeTexImage"]
    assert len({n.location.x for n in images}) == 1 and len({n.location.y for n in images}) == len(images)


def test_images_sizes_and_tiling(tmp_path):
    material = build_material(make_result(tmp_path / "r"), tiling=3.0)
    tree = material.node_tree
    assert tuple(tree.nodes["Tiling"].inputs["Scale"].default_value) == pytest.approx((3.0, 3.0, 1.0))
    assert linked(tree, "Texture Coordinate", "UV", "Tiling", "Vector")
    usages = {"Base Color": "basecolor", "Roughness": "roughness", "Metallic": "metallic", "Normal": "normal",
              "Height": "height"}
    for name, usage in usages.items():
        image = tree.nodes[name].image
        assert image.name == f"Match marble {usage}" and tuple(image.size) == (W, H)
        assert linked(tree, "Tiling", "Vector", name, "Vector")
    assert not any("ambientocclusion" in image.name for image in bpy.data.images)


def test_the_mapping_carries_the_fitted_zoom_times_the_tiling(tmp_path):
    """params.json's "calibration.zoom" (texture periods across the photo) scales the UVs with the
    user's tiling; rebuilding from the material recovers the user's tiling alone, not the product."""
    from blender_match.blender.match_job import material_tiling

    params = {"graph": "marble", "params": {**PARAMS["params"], f"{CALIBRATION}.{ZOOM}": 2.0}}
    material = build_material(make_result(tmp_path / "r", params=params), tiling=1.5)
    assert tuple(material.node_tree.nodes["Tiling"].inputs["Scale"].default_value) == pytest.approx((3.0, 3.0, 1.0))
    assert material_tiling(material) == pytest.approx(1.5)
    plain = build_material(make_result(tmp_path / "p"), tiling=1.5)  # a result from before the zoom
    assert material_tiling(plain) == pytest.approx(1.5)


def test_flat_maps_become_default_values(tmp_path):
    flat = {"basecolor": 0.5, "roughness": 0.25, "normal": 0.5, "height": 0.5}
    tree = build_material(make_result(tmp_path / "r", flat=flat)).node_tree
    images = {n.name for n in tree.nodes if n.bl_idname == "ShaderNodeTexImage"}
    assert images == {"Metallic"}
    assert node_types(tree).count("ShaderNodeNormalMap") == 0
    assert node_types(tree).count("ShaderNodeDisplacement") == 0
    principled = tree.nodes["Principled BSDF"]
    linear = float(srgb_to_linear(0.5))
    assert tuple(principled.inputs["Base Color"].default_value) == pytest.approx((linear, linear, linear, 1.0))
    assert linear == pytest.approx(0.2140, abs=1e-4)
    assert principled.inputs["Roughness"].default_value == pytest.approx(0.25)
    assert not principled.inputs["Normal"].is_linked
    assert not tree.nodes["Material Output"].inputs["Displacement"].is_linked
    assert len(bpy.data.images) == 1


def test_all_maps_flat_needs_no_coordinates(tmp_path):
    flat = {u: 0.5 for u in USAGES}
    tree = build_material(make_result(tmp_path / "r", flat=flat)).node_tree
    assert node_types(tree) == ["ShaderNodeBsdfPrincipled", "ShaderNodeOutputMaterial"]
    anisotropic = build_material(make_result(tmp_path / "a", flat=flat, anisotropy=True)).node_tree
    assert node_types(anisotropic) == ["ShaderNodeBsdfPrincipled", "ShaderNodeOutputMaterial", "ShaderNodeTangent"]


def test_anisotropy_maps_feed_the_principled_bsdf_with_a_uv_tangent(tmp_path):
    """The level goes to "Anisotropic"; the angle (the brushing's) plus a quarter turn to
    "Anisotropic Rotation" (the direction the highlight stretches along, across the brushing);
    a Tangent node of the UV map, the one the images read, makes it turn from the texture's +u."""
    tree = build_material(make_result(tmp_path / "r", anisotropy=True)).node_tree
    assert linked(tree, "Anisotropy", "Color", "Principled BSDF", "Anisotropic")
    assert linked(tree, "Anisotropy Angle", "Color", "Anisotropic Rotation", "Value")
    assert linked(tree, "Anisotropic Rotation", "Value", "Principled BSDF", "Anisotropic Rotation")
    turn = tree.nodes["Anisotropic Rotation"]
    assert turn.operation == "ADD" and turn.inputs[1].default_value == pytest.approx(0.25)
    tangent = tree.nodes["Tangent"]
    assert (tangent.direction_type, tangent.uv_map) == ("UV_MAP", "")  # "": the active UV map, as the images'
    assert linked(tree, "Tangent", "Tangent", "Principled BSDF", "Tangent")
    assert linked(tree, "Tiling", "Vector", "Anisotropy", "Vector")
    assert linked(tree, "Tiling", "Vector", "Anisotropy Angle", "Vector")
    for name in ("Anisotropy", "Anisotropy Angle"):
        assert tree.nodes[name].image.colorspace_settings.name == "Non-Color"
    x = {node.name: node.location.x for node in tree.nodes}
    assert x["Anisotropy Angle"] < x["Anisotropic Rotation"] < x["Principled BSDF"]
    assert x["Tangent"] < x["Principled BSDF"]


def test_flat_anisotropy_becomes_values_and_a_flat_zero_adds_nothing(tmp_path):
    flat = {ANISOTROPY: 0.7, ANISOTROPY_ANGLE: 0.875}
    tree = build_material(make_result(tmp_path / "r", flat=flat, anisotropy=True)).node_tree
    principled = tree.nodes["Principled BSDF"]
    assert principled.inputs["Anisotropic"].default_value == pytest.approx(0.7)
    assert principled.inputs["Anisotropic Rotation"].default_value == pytest.approx(0.125)  # 0.875 + 0.25, mod 1
    assert linked(tree, "Tangent", "Tangent", "Principled BSDF", "Tangent")
    images = {n.name for n in tree.nodes if n.bl_idname == "ShaderNodeTexImage"}
    assert "Anisotropy" not in images and "Anisotropy Angle" not in images
    isotropic = build_material(make_result(tmp_path / "z", flat={ANISOTROPY: 0.0}, anisotropy=True)).node_tree
    assert "ShaderNodeTangent" not in node_types(isotropic) and "ShaderNodeMath" not in node_types(isotropic)
    assert not any("anisotropyangle" in image.name for image in bpy.data.images if image.name.startswith("Match"))
    assert isotropic.nodes["Principled BSDF"].inputs["Anisotropic"].default_value == 0.0


def test_the_built_material_renders_in_cycles_as_our_renderer(tmp_path):
    """End to end: a result folder with an angle map of 1/8 turn (brushed towards +u+v), built
    and rendered by Cycles under the flash, stretches its highlight along -u+v, as ours does."""
    from cycles_flash import CyclesFlash, highlight

    flat = {"basecolor": 0.8, "roughness": 0.5, "metallic": 1.0, "normal": 0.5, "height": 0.5, ANISOTROPY: 0.8}
    result = make_result(tmp_path / "r", flat=flat, ao=False, anisotropy=True)
    write_png(result / "anisotropyangle.png", torch.full((1, 1, H, W), 32 / 255), bits=8, overwrite=True)
    cycles = CyclesFlash(bpy, tmp_path / "cycles")
    cycles.use(build_material(result))
    axis, aspect = highlight(cycles.render_scene())
    assert abs(axis - (0.125 + 0.25) * 360 % 180) < 1.5 and aspect > 2.0


def test_second_build_makes_new_material_and_images(tmp_path):
    result = make_result(tmp_path / "r")
    users = bpy.data.materials.new("Match marble")
    users.diffuse_color = (1.0, 0.0, 0.0, 1.0)
    first = build_material(result)
    first_images = {n.image.name for n in first.node_tree.nodes if n.bl_idname == "ShaderNodeTexImage"}
    second = build_material(result)
    second_images = {n.image.name for n in second.node_tree.nodes if n.bl_idname == "ShaderNodeTexImage"}
    assert len({users.name, first.name, second.name}) == 3 and len(bpy.data.materials) == 3
    assert users.node_tree is None or len(users.node_tree.nodes) == 2  # the user's material is untouched
    assert tuple(users.diffuse_color) == (1.0, 0.0, 0.0, 1.0)
    assert not first_images & second_images and len(bpy.data.images) == 10
    assert all(n.image.name in first_images for n in first.node_tree.nodes if n.bl_idname == "ShaderNodeTexImage")


def test_name_option(tmp_path):
    material = build_material(make_result(tmp_path / "r"), name="Wall")
    assert material.name == "Wall"
    assert "Wall basecolor" in bpy.data.images


def test_pack_option_packs_images(tmp_path):
    result = make_result(tmp_path / "r")
    loose = build_material(result)
    packed = build_material(result, pack=True)
    for material, is_packed in ((loose, False), (packed, True)):
        images = [n.image for n in material.node_tree.nodes if n.bl_idname == "ShaderNodeTexImage"]
        assert images and all((image.packed_file is not None) == is_packed for image in images)


def test_custom_property_round_trips_params(tmp_path):
    result = make_result(tmp_path / "r")
    record = build_material(result)["blender_match"].to_dict()
    assert json.loads(record["params"]) == PARAMS
    assert record["graph"] == "marble" and record["size"] == W
    assert record["loss"] == pytest.approx(0.125)
    assert record["result_dir"] == str(result.resolve())


def test_an_automatic_match_keeps_the_graphs_ranked_next_and_its_origin(tmp_path):
    # the kept graph need not be the ranking's first (a final choice among fitted candidates)
    result = make_result(tmp_path / "auto", graph="granite", ranking=["asphalt", "granite", "rough_stone", "gravel"])
    origin = {"photo": "//photos/gravel.jpg", "quality": "draft", "params": "not taken"}
    record = build_material(result, origin=origin)["blender_match"].to_dict()
    assert record["alternatives"] == ["asphalt", "rough_stone"]
    assert record["photo"] == "//photos/gravel.jpg" and record["quality"] == "draft"
    assert json.loads(record["params"]) == PARAMS  # only what a match came from is taken from the origin
    assert ranked_alternatives({"graph": "granite", "ranking": [{"graph": "granite"}]}) == []
    # an automatic match's own ranking comes before alternatives handed down
    handed = {**origin, "alternatives": ["felt"]}
    assert build_material(result, origin=handed)["blender_match"]["alternatives"] == ["asphalt", "rough_stone"]
    # a named match: no ranking; it offers only what it was handed (an earlier automatic match's)
    named = build_material(make_result(tmp_path / "named"))["blender_match"].to_dict()
    assert "alternatives" not in named and "photo" not in named
    assert build_material(make_result(tmp_path / "named2"), origin=handed)["blender_match"]["alternatives"] == ["felt"]


def test_graph_path_names_the_material_by_its_stem(tmp_path):
    material = build_material(make_result(tmp_path / "r", graph="/graphs/rusty_metal.sbs"))
    assert material.name == "Match rusty_metal"


def test_assign_replaces_only_the_active_slot_link(tmp_path):
    material = build_material(make_result(tmp_path / "r"))
    old = bpy.data.materials.new("old")
    obj = bpy.data.objects.new("plane", bpy.data.meshes.new("plane"))
    obj.data.materials.append(old)
    assert assign_material(obj, material)
    assert obj.active_material == material and len(obj.material_slots) == 1
    assert "old" in bpy.data.materials


def test_assign_appends_a_slot_when_there_is_none(tmp_path):
    material = build_material(make_result(tmp_path / "r"))
    obj = bpy.data.objects.new("plane", bpy.data.meshes.new("plane"))
    assert assign_material(obj, material)
    assert [slot.material for slot in obj.material_slots] == [material]


def test_objects_without_materials_are_refused(tmp_path):
    material = build_material(make_result(tmp_path / "r"))
    empty = bpy.data.objects.new("empty", None)
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    assert not assign_material(empty, material)
    assert not assign_material(camera, material)


def test_missing_report_is_a_one_line_error_naming_the_folder(tmp_path):
    folder = tmp_path / "not_a_result"
    folder.mkdir()
    with pytest.raises(ResultFolderError) as info:
        build_material(folder)
    assert str(folder) in str(info.value) and "report.json" in str(info.value)
    assert "\n" not in str(info.value)
    assert len(bpy.data.materials) == 0


def test_missing_map_file_creates_nothing(tmp_path):
    result = make_result(tmp_path / "r")
    (result / "normal.png").unlink()
    with pytest.raises(ResultFolderError, match="normal.png"):
        build_material(result)
    assert len(bpy.data.materials) == 0 and len(bpy.data.images) == 0
