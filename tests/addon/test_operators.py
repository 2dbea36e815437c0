"""The add-on's operators in the real bpy module, with real worker processes (no mocks).

One Blender session (a subprocess: enabling an add-on in-process would leak into other tests)
installs the built extension zip into a temporary BLENDER_USER_RESOURCES, points the worker
Python preference at this test environment's Python, and then, on a saved .blend with a plane
that already has a material:

* matches the plaster photo (``match_photo(..., wait=True)``) and records the material built;
* exports its maps with each preset, re-renders it at 1K, edits a parameter and applies it;
* drives the shared job controller (``blender.match_job``, what the modal operator polls) to
  cancel a match mid-fit, kills a worker mid-fit, and runs a match with a missing backend and one
  with an unknown graph, recording that the file is unchanged each time;
* disables the add-on while a job runs and records what is left.

The session prints one JSON line; the tests below check its parts.
"""
from __future__ import annotations

import json
import os
import textwrap
from pathlib import Path

import pytest
from blender_session import run_blender_script

from blender_match.cli import main

pytestmark = pytest.mark.slow  # one Blender session installs the built extension and runs jobs


SESSION = textwrap.dedent(r"""
    import importlib, json, os, signal, sys, time
    from pathlib import Path
    import bpy

    ZIP, PHOTO, WORK = sys.argv[1], sys.argv[2], Path(sys.argv[3])
    MOD = "bl_ext.user_default.blender_match"
    out = {"seconds": {}}
    T0 = time.monotonic()

    def mark(step):
        out["seconds"][step] = round(time.monotonic() - T0, 1)
    types_before = set(dir(bpy.types))
    out["install"] = sorted(bpy.ops.extensions.package_install_files(
        filepath=ZIP, repo="user_default", enable_on_install=True))
    prefs = bpy.context.preferences.addons[MOD].preferences
    prefs.worker_python = sys.executable
    match_job = importlib.import_module(MOD + ".blender.match_job")
    mark("install")
    out["torch_in_blender"] = "torch" in sys.modules

    # a saved file with a plane whose slot holds an existing material
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    bpy.ops.mesh.primitive_plane_add(size=2)
    plane = bpy.context.view_layer.objects.active
    existing = bpy.data.materials.new("Existing")
    plane.data.materials.append(existing)
    blend = WORK / "scene.blend"
    bpy.ops.wm.save_as_mainfile(filepath=str(blend))
    plane = bpy.data.objects[plane.name]
    results = WORK / "blender_match"

    def state():
        return {"materials": sorted(m.name for m in bpy.data.materials),
                "images": sorted(i.name for i in bpy.data.images),
                "slots": [s.material.name if s.material else None for s in plane.material_slots],
                "folders": sorted(p.name for p in results.iterdir()) if results.is_dir() else []}

    def material_info(mat):
        tree = mat.node_tree
        images = {}
        for node in tree.nodes:
            if node.bl_idname == "ShaderNodeTexImage":
                img = node.image
                images[node.label] = {"name": img.name, "size": list(img.size),
                                      "colorspace": img.colorspace_settings.name,
                                      "file": bpy.path.abspath(img.filepath), "relative": img.filepath.startswith("//"),
                                      "packed": img.packed_file is not None}
        bsdf = next(n for n in tree.nodes if n.bl_idname == "ShaderNodeBsdfPrincipled")
        record = mat["blender_match"].to_dict()
        return {"name": mat.name,
                "nodes": sorted(n.bl_idname for n in tree.nodes),
                "links": sorted([l.from_node.bl_idname, l.from_socket.name, l.to_node.bl_idname, l.to_socket.name]
                                for l in tree.links),
                "images": images,
                "metallic": {"linked": bsdf.inputs["Metallic"].is_linked,
                             "value": bsdf.inputs["Metallic"].default_value},
                "record": {k: v for k, v in record.items() if k != "params"},
                "params": json.loads(record["params"]),
                "sliders": {item.name: (list(item.color) if item.kind == "COLOR" else item.value)
                            for item in mat.blender_match_params},
                "mapping_scale": list(tree.nodes["Tiling"].inputs["Scale"].default_value)}

    def run_op(op, **kwargs):
        try:
            return {"result": sorted(op(**kwargs)), "error": None}
        except RuntimeError as exc:
            return {"result": None, "error": str(exc)}

    def poll_until_fitting(job, iteration=True, timeout=300):
        # until the first fitting event (with iteration: the first one after an iteration)
        deadline = time.monotonic() + timeout
        while not job.poll() and time.monotonic() < deadline:
            p = job.progress or {}
            if p.get("stage") == "fitting" and (not iteration or p.get("iteration") is not None):
                return {"stage_text": job.stage_text, "progress_text": job.progress_text(), "fraction": job.fraction}
            time.sleep(0.05)
        return None

    # --- match ---------------------------------------------------------------------------------
    before = state()
    t0 = time.monotonic()
    out["match"] = run_op(bpy.ops.blender_match.match_photo, filepath=PHOTO, graph="plaster", quality="draft",
                          iterations=2, wait=True, alternatives="stucco,plaster,painted_wall")
    out["match"]["seconds"] = round(time.monotonic() - t0, 1)
    plane = bpy.data.objects[plane.name]
    matched = plane.active_material
    out["matched"] = material_info(matched)
    out["after_match"] = state()
    out["existing_still_there"] = "Existing" in bpy.data.materials
    out["last"] = match_job.LAST.get(bpy.context.scene.session_uid)
    out["blend_dir"] = str(blend.parent)
    mark("match")

    # --- export --------------------------------------------------------------------------------
    out["export"] = {}
    for preset in ("gltf", "unreal", "unity"):
        target = WORK / "export" / preset
        r = run_op(bpy.ops.blender_match.export_maps, preset=preset, directory=str(target), size=256)
        r["files"] = sorted(p.name for p in target.iterdir()) if target.is_dir() else []
        out["export"][preset] = r
    r = run_op(bpy.ops.blender_match.export_maps, preset="gltf", directory=str(WORK / "export" / "gltf"), size=256)
    out["export_again"] = r  # refused: the files exist and overwrite is off
    r = run_op(bpy.ops.blender_match.export_maps, preset="unreal", directory=str(WORK / "export" / "exr"),
               size=128, file_format="OPEN_EXR", bits=16)
    r["files"] = sorted(p.name for p in (WORK / "export" / "exr").iterdir())
    out["export_exr"] = r
    mark("export")

    # --- re-render at 1K -----------------------------------------------------------------------
    old_images = {k: (v["name"], v["size"], v["file"]) for k, v in out["matched"]["images"].items()}
    out["rerender"] = run_op(bpy.ops.blender_match.rerender, size="1K", wait=True)
    rerendered = plane.active_material
    out["rerendered"] = material_info(rerendered)
    old = bpy.data.materials.get(matched.name)
    out["old_after_rerender"] = material_info(old) if old else None
    out["old_images_after_rerender"] = {k: (v["name"], v["size"], v["file"])
                                        for k, v in (out["old_after_rerender"] or {"images": {}})["images"].items()}
    out["old_images_before_rerender"] = old_images
    mark("rerender")

    # --- edit a parameter and apply ------------------------------------------------------------
    item = rerendered.blender_match_params["roughness"]
    item.value_wide = 5.0          # clamped to the graph's range
    out["clamped_roughness"] = item.value
    item.value = 0.93
    rerendered.blender_match_params["color"].color = (0.3, 0.4, 0.5)
    out["apply"] = run_op(bpy.ops.blender_match.apply_parameters, size="1K", wait=True)
    edited = plane.active_material
    out["edited"] = material_info(edited)
    out["edited_folder_params"] = json.loads(
        (Path(out["edited"]["record"]["result_dir"]) / "params.json").read_text())["params"]
    out["rerendered_still_there"] = rerendered.name in bpy.data.materials
    out["after_edits"] = state()
    mark("apply")

    # --- cancel mid-fit through the controller -------------------------------------------------
    before = state()
    job = match_job.start_match(bpy.context, photo=PHOTO, graph="plaster", size=256, quality="draft",
                                iterations=300, device="cpu")
    folder = job.out_dir
    out["cancel_progress"] = poll_until_fitting(job)
    out["running_during"] = match_job.running_job(bpy.context.scene) is job
    job.cancel()
    job.wait(timeout=120)
    out["cancel"] = {"state": job.state, "message": job.message, "folder_left": folder.exists(),
                     "same": state() == before, "state_after": state(), "state_before": before,
                     "registered": bpy.context.scene.session_uid in match_job.JOBS,
                     "last": match_job.LAST.get(bpy.context.scene.session_uid)}
    mark("cancel")

    # --- a killed worker -----------------------------------------------------------------------
    job = match_job.start_match(bpy.context, photo=PHOTO, graph="plaster", size=256, quality="draft",
                                iterations=300, device="cpu")
    folder = job.out_dir
    out["kill_progress"] = poll_until_fitting(job, iteration=False)
    os.kill(job.pid, signal.SIGKILL)
    job.wait(timeout=120)
    out["kill"] = {"state": job.state, "message": job.message, "folder_left": folder.exists(),
                   "same": state() == before, "last": match_job.LAST.get(bpy.context.scene.session_uid)}
    mark("kill")

    # --- a worker error (unknown graph) and a missing backend ----------------------------------
    r = run_op(bpy.ops.blender_match.match_photo, filepath=PHOTO, graph="no_such_graph", iterations=2, wait=True)
    r["same"] = state() == before
    out["unknown_graph"] = r
    prefs.worker_python = str(WORK / "no" / "python")
    r = run_op(bpy.ops.blender_match.match_photo, filepath=PHOTO, graph="plaster", iterations=2, wait=True)
    r["same"] = state() == before
    out["missing_backend"] = r
    mark("errors")
    prefs.worker_python = sys.executable

    # --- an image datablock as the photo -------------------------------------------------------
    loaded = bpy.data.images.load(PHOTO, check_existing=False)
    path, temporary = match_job.image_photo(loaded)
    out["image_on_disk"] = [str(path), temporary]
    generated = bpy.data.images.new("generated photo", 32, 16)
    path, temporary = match_job.image_photo(generated)
    written = bpy.data.images.load(str(path), check_existing=False)
    out["image_generated"] = [temporary, path.suffix, list(written.size)]
    bpy.data.images.remove(written)
    path.unlink()
    bpy.data.images.remove(loaded)
    bpy.data.images.remove(generated)

    # --- disable while a job runs: nothing left ------------------------------------------------
    before = state()
    job = match_job.start_match(bpy.context, photo=PHOTO, graph="plaster", size=256, quality="draft",
                                iterations=300, device="cpu")
    folder, process = job.out_dir, job.worker.process
    bpy.ops.preferences.addon_disable(module=MOD)
    out["disable"] = {"enabled": MOD in bpy.context.preferences.addons,
                      "worker_exit": process.poll(), "folder_left": folder.exists(), "same": state() == before,
                      "jobs": len(match_job.JOBS), "timers": len(match_job.TIMERS),
                      "scene_prop": hasattr(bpy.types.Scene, "blender_match"),
                      "material_prop": hasattr(bpy.types.Material, "blender_match_params"),
                      "new_types": sorted(set(dir(bpy.types)) - types_before)}
    try:
        bpy.ops.blender_match.match_photo.get_rna_type()
        out["disable"]["op_still_registered"] = True
    except (KeyError, AttributeError, RuntimeError):
        out["disable"]["op_still_registered"] = False
    mark("disable")
    print("RESULT " + json.dumps(out))
""")


@pytest.fixture(scope="module")
def session(tmp_path_factory, plaster_photo) -> dict:
    dist = tmp_path_factory.mktemp("dist")
    assert main(["build-extension", "--out", str(dist)]) == 0
    [zip_path] = dist.glob("*.zip")
    work = tmp_path_factory.mktemp("work")
    env = {**os.environ, "BLENDER_USER_RESOURCES": str(work / "blender-user")}
    out = run_blender_script(SESSION, [str(zip_path), str(plaster_photo), str(work)], work, env, timeout=900)
    out["work"] = str(work)
    out["photo"] = str(plaster_photo)
    return out


def _result_dir(material: dict) -> Path:
    return Path(material["record"]["result_dir"])


def test_installed_extension_registers_without_torch(session):
    assert session["install"] == ["FINISHED"]
    assert not session["torch_in_blender"]


def test_match_builds_a_new_material_in_the_active_slot(session):
    assert session["match"] == {"result": ["FINISHED"], "error": None, "seconds": session["match"]["seconds"]}
    mat = session["matched"]
    nodes = mat["nodes"]
    assert {"ShaderNodeBsdfPrincipled", "ShaderNodeNormalMap", "ShaderNodeMapping", "ShaderNodeTexCoord",
            "ShaderNodeOutputMaterial"} <= set(nodes)
    report = json.loads((_result_dir(mat) / "report.json").read_text())
    assert report["maps"]["metallic"]["flat"] is not None  # plaster is not metallic: a flat map
    image_maps = [u for u in ("basecolor", "roughness", "metallic", "normal", "height")
                  if u in report["maps"] and report["maps"][u]["flat"] is None]
    assert nodes.count("ShaderNodeTexImage") == len(image_maps) == len(mat["images"]) == 4
    links = {tuple(link) for link in mat["links"]}
    for link in [("ShaderNodeTexImage", "Color", "ShaderNodeBsdfPrincipled", "Base Color"),
                 ("ShaderNodeTexImage", "Color", "ShaderNodeBsdfPrincipled", "Roughness"),
                 ("ShaderNodeTexImage", "Color", "ShaderNodeNormalMap", "Color"),
                 ("ShaderNodeNormalMap", "Normal", "ShaderNodeBsdfPrincipled", "Normal"),
                 ("ShaderNodeTexCoord", "UV", "ShaderNodeMapping", "Vector"),
                 ("ShaderNodeMapping", "Vector", "ShaderNodeTexImage", "Vector"),
                 ("ShaderNodeBsdfPrincipled", "BSDF", "ShaderNodeOutputMaterial", "Surface")]:
        assert link in links, link
    assert "Metallic" not in mat["images"] and not mat["metallic"]["linked"]
    assert mat["metallic"]["value"] == pytest.approx(report["maps"]["metallic"]["flat"][0])
    assert mat["images"]["Base Color"]["colorspace"] == "sRGB"
    assert {k: v["colorspace"] for k, v in mat["images"].items() if k != "Base Color"} == {
        "Roughness": "Non-Color", "Normal": "Non-Color", "Height": "Non-Color"}
    for image in mat["images"].values():
        assert image["size"] == [2048, 2048]  # the default size
        assert Path(image["file"]).is_file() and not image["packed"]  # saved .blend: files, not packed
        assert image["relative"]  # "//blender_match/...": the project folder can move
    # next to the .blend, in a new folder named after the graph
    folder = _result_dir(mat)
    assert folder.parent == Path(session["blend_dir"]) / "blender_match"
    assert folder.name.startswith("plaster_")
    assert session["after_match"]["slots"] == [mat["name"]]
    assert session["existing_still_there"]
    # what re-rendering and editing need, on the material
    assert mat["record"]["graph"] == "plaster" and mat["record"]["size"] == 2048
    # what the match came from, for matching another graph to the same photo: the photo, the
    # quality, and the graphs an earlier automatic match ranked with this one (given to the
    # operator, as the panel's "Also close" buttons do; the matched graph itself left out)
    assert mat["record"]["photo"] == session["photo"] and mat["record"]["quality"] == "draft"
    assert mat["record"]["alternatives"] == ["stucco", "painted_wall"]
    assert mat["params"]["graph"] == "plaster" and mat["params"]["source"] == "plaster"
    exposed = {k[len("exposed."):]: v for k, v in mat["params"]["params"].items() if k.startswith("exposed.")}
    assert set(mat["sliders"]) == set(exposed) == {"color", "bump_scale", "bumps", "trowel", "roughness", "relief"}
    for name, value in mat["sliders"].items():
        assert value == pytest.approx(exposed[name], abs=1e-5)
    # the photo's exposure and white balance, calibrated by default, stored for re-renders
    assert mat["params"]["params"]["calibration.basecolor_gain"] == pytest.approx(
        report["calibration"]["basecolor_gain"], abs=1e-4)
    # the texture's scale in the photo, searched by default, carried by the Mapping node (tiling 1)
    zoom = report["calibration"]["zoom"]
    assert mat["params"]["params"]["calibration.zoom"] == zoom
    assert mat["mapping_scale"] == pytest.approx([zoom, zoom, 1.0])
    last = session["last"]
    assert last["state"] == "finished" and last["material"] == mat["name"] and last["graph"] == "plaster"
    assert isinstance(last["loss"], float) and last["seconds"] > 0


def test_export_maps_writes_each_preset(session):
    files = {preset: r["files"] for preset, r in session["export"].items()}
    assert all(r["result"] == ["FINISHED"] for r in session["export"].values()), session["export"]
    assert files == {
        "gltf": ["plaster_baseColor.png", "plaster_metallicRoughness.png", "plaster_normal.png"],
        "unreal": ["plaster_BaseColor.png", "plaster_Normal.png", "plaster_ORM.png"],
        "unity": ["plaster_Albedo.png", "plaster_Height.png", "plaster_MetallicSmoothness.png", "plaster_Normal.png",
                  "plaster_Occlusion.png"]}
    for preset, names in files.items():
        for name in names:
            assert (Path(session["work"]) / "export" / preset / name).stat().st_size > 0
    again = session["export_again"]
    assert again["result"] is None and "already exists" in again["error"]
    assert session["export_exr"]["result"] == ["FINISHED"]
    assert session["export_exr"]["files"] == ["plaster_BaseColor.exr", "plaster_Normal.exr", "plaster_ORM.exr"]


def test_rerender_at_1k_makes_a_new_material_and_keeps_the_old(session):
    assert session["rerender"] == {"result": ["FINISHED"], "error": None}
    new, old = session["rerendered"], session["old_after_rerender"]
    assert old is not None and new["name"] != old["name"]
    assert {v["size"][0] for v in new["images"].values()} == {1024}
    assert {v["size"][0] for v in old["images"].values()} == {2048}
    assert session["old_images_after_rerender"] == session["old_images_before_rerender"]
    assert _result_dir(new) != _result_dir(old) and _result_dir(new).name.startswith("plaster_1K_")
    assert new["params"]["params"] == old["params"]["params"]  # the same material, another size
    assert (new["record"]["photo"], new["record"]["quality"], new["record"]["alternatives"]) == (
        session["photo"], "draft", ["stucco", "painted_wall"])  # carried on
    assert set(new["nodes"]) == set(old["nodes"])


def test_apply_edited_parameters(session):
    assert session["clamped_roughness"] == pytest.approx(1.0)  # plaster's roughness range is [0.4, 1]
    assert session["apply"] == {"result": ["FINISHED"], "error": None}
    edited, before = session["edited"], session["rerendered"]
    params = edited["params"]["params"]
    assert params["exposed.roughness"] == pytest.approx(0.93, abs=1e-5)
    assert params["exposed.color"][:3] == pytest.approx([0.3, 0.4, 0.5], abs=1e-5)
    assert session["edited_folder_params"]["exposed.roughness"] == pytest.approx(0.93, abs=1e-5)
    unchanged = {k: v for k, v in before["params"]["params"].items()
                 if k not in ("exposed.roughness", "exposed.color")}
    assert {k: params[k] for k in unchanged} == unchanged
    assert edited["sliders"]["roughness"] == pytest.approx(0.93, abs=1e-5)
    assert _result_dir(edited).name.startswith("plaster_edit_")
    assert session["after_edits"]["slots"] == [edited["name"]]
    assert session["rerendered_still_there"]
    assert len(session["after_edits"]["folders"]) == 3


def test_cancel_mid_fit_leaves_the_file_unchanged(session):
    progress = session["cancel_progress"]
    assert progress is not None, "no fitting progress before the job ended"
    assert progress["stage_text"].startswith("Fitting graph 1 of 1 (plaster), iteration ")
    assert "left" in progress["progress_text"] and 0 < progress["fraction"] < 1
    assert session["running_during"]
    cancel = session["cancel"]
    assert cancel["state"] == "cancelled" and "nothing was changed" in cancel["message"]
    assert cancel["same"], (cancel["state_before"], cancel["state_after"])
    assert not cancel["folder_left"] and not cancel["registered"]
    assert cancel["last"]["state"] == "cancelled"


def test_killed_worker_reports_an_error_and_changes_nothing(session):
    assert session["kill_progress"] is not None
    kill = session["kill"]
    assert kill["state"] == "failed"
    assert "exited" in kill["message"] and "SIGKILL" in kill["message"]
    assert kill["same"] and not kill["folder_left"]
    assert kill["last"]["error"] == kill["message"]


def test_worker_error_and_missing_backend_cancel_with_a_clear_message(session):
    unknown = session["unknown_graph"]
    assert unknown["result"] is None and "no_such_graph: not a bundled graph" in unknown["error"]
    assert unknown["same"]
    missing = session["missing_backend"]
    assert missing["result"] is None
    assert missing["error"].startswith("Error: No matching backend: set it up in Preferences > Add-ons > Blender Match")
    assert "does not exist" in missing["error"] and missing["same"]


def test_an_image_datablock_as_the_photo(session, plaster_photo):
    assert session["image_on_disk"] == [str(plaster_photo), False]  # its own file, unchanged on disk
    assert session["image_generated"] == [True, ".png", [32, 16]]  # written to a temporary PNG


def test_disabling_during_a_job_leaves_nothing_behind(session):
    disable = session["disable"]
    assert not disable["enabled"]
    assert disable["worker_exit"] is not None  # the worker was stopped
    assert not disable["folder_left"] and disable["same"]
    assert disable["jobs"] == 0 and disable["timers"] == 0
    assert not disable["scene_prop"] and not disable["material_prop"] and not disable["op_still_registered"]
    assert disable["new_types"] == []
