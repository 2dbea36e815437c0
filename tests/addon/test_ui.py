"""The add-on's panel, preferences and settings in the real bpy module, with real worker processes.

Blender in the background has no window to draw a panel in, and a ``bpy.types.Panel`` cannot be
instantiated outside Blender's drawing. The panel's draw code is one function,
``ui.panel.draw_match_panel(layout, context)`` (the two Panel classes only call it), so the test
runs it for real with a *layout recorder* in place of ``bpy.types.UILayout``: an object with the
UILayout methods the draw code uses (row, column, box, prop, operator, label, progress,
template_icon_view, separator), which checks every call against the real RNA — each keyword is a
parameter of that UILayout function, each property exists on the data's RNA, each operator id is a
registered ``bpy.ops`` operator and every property set on an operator button exists on it (with a
valid enum value) — and records what would be drawn. Only the layout is stood in for; the scene,
the jobs (real workers), the operators and the properties are Blender's own.

One Blender session (a subprocess) enables the add-on as a plain module (not an extension, which
exercises the fallbacks for that case) and draws the panel: idle; during a match run by the
operator in an unsaved file (drawn from the controller's polling, at the first fitting event and
after the first iteration); after it; as a job starts, is cancelled with the Cancel operator and
ends. It then draws the preferences, runs the worker probe and a backend setup that cannot work,
and disables the add-on.
"""
from __future__ import annotations

import os
import struct
import textwrap
from pathlib import Path

import pytest
from blender_session import run_blender_script
from conftest import ROOT

from blender_match.errors import OptionError
from blender_match.library.catalog import USER_LIBRARY_ENV
from blender_match.library.thumbnails import write_thumbnails
from blender_match.library.user import add_entry

GRAPHS = ROOT / "blender_match" / "library" / "graphs"

SESSION = textwrap.dedent(r"""
    import importlib, json, os, sys, time
    from types import SimpleNamespace
    import bpy, addon_utils

    PHOTO, USER_LIBRARY = sys.argv[1:3]
    out = {"seconds": {}}
    T0 = time.monotonic()

    def mark(step):
        out["seconds"][step] = round(time.monotonic() - T0, 1)
    types_before = set(dir(bpy.types))
    addon_utils.enable("blender_match", default_set=True, handle_error=None)
    out["enabled"] = "blender_match" in bpy.context.preferences.addons
    prefs = bpy.context.preferences.addons["blender_match"].preferences
    prefs.worker_python = sys.executable
    panel = importlib.import_module("blender_match.ui.panel")
    preferences = importlib.import_module("blender_match.preferences")
    properties = importlib.import_module("blender_match.blender.properties")
    addon = importlib.import_module("blender_match.blender.addon")
    match_job = importlib.import_module("blender_match.blender.match_job")
    out["backend_dir"] = str(addon.backend_dir())

    UI = bpy.types.UILayout.bl_rna

    class Operator:
        def __init__(self, idname, log):
            module, name = idname.split(".")
            rna = getattr(getattr(bpy.ops, module), name).get_rna_type()
            object.__setattr__(self, "_rna", rna)
            object.__setattr__(self, "_entry", log)

        def __setattr__(self, key, value):
            prop = self._rna.properties.get(key)
            assert prop is not None, f"{self._rna.identifier} has no property {key!r}"
            if prop.type == "ENUM":
                assert value in {i.identifier for i in prop.enum_items}, (key, value)
            self._entry["props"][key] = value

    class Layout:
        # UILayout stand-in: checks each call against the RNA, records what is drawn.
        def __init__(self, log, depth=0):
            object.__setattr__(self, "_log", log)
            object.__setattr__(self, "_depth", depth)

        def __setattr__(self, key, value):
            assert key in UI.properties, f"UILayout has no attribute {key!r}"

        def _check(self, function, kwargs):
            params = {p.identifier for p in UI.functions[function].parameters}
            assert set(kwargs) <= params, f"UILayout.{function}: unknown {set(kwargs) - params}"
            for key in ("text", "icon"):
                assert key not in kwargs or isinstance(kwargs[key], str), (function, key, kwargs[key])
            if "icon" in kwargs:
                icons = bpy.types.UILayout.bl_rna.functions["prop"].parameters["icon"].enum_items
                assert kwargs["icon"] in icons, f"unknown icon {kwargs['icon']}"

        def _sub(self, function, **kwargs):
            self._check(function, kwargs)
            return Layout(self._log, self._depth + 1)

        def row(self, **kw): return self._sub("row", **kw)
        def column(self, **kw): return self._sub("column", **kw)
        def box(self, **kw): return self._sub("box", **kw)
        def split(self, **kw): return self._sub("split", **kw)

        def separator(self, **kw):
            self._check("separator", kw)

        def label(self, **kw):
            self._check("label", kw)
            self._log.append({"kind": "label", "text": kw.get("text", "")})

        def _prop(self, function, data, prop, **kw):
            self._check(function, kw)
            assert prop in data.bl_rna.properties, f"{data.bl_rna.identifier} has no property {prop!r}"
            self._log.append({"kind": function, "data": data.bl_rna.identifier, "prop": prop,
                              "text": kw.get("text"), "slider": kw.get("slider", False)})

        def prop(self, data, property, **kw): self._prop("prop", data, property, **kw)
        def template_icon_view(self, data, property, **kw): self._prop("template_icon_view", data, property, **kw)

        def progress(self, **kw):
            self._check("progress", kw)
            assert 0.0 <= kw.get("factor", 0.0) <= 1.0
            self._log.append({"kind": "progress", "factor": kw.get("factor"), "text": kw.get("text", "")})

        def operator(self, operator, **kw):
            self._check("operator", kw)
            entry = {"kind": "operator", "id": operator, "text": kw.get("text"), "props": {}}
            self._log.append(entry)
            return Operator(operator, entry)

    def draw(draw_function=None):
        log = []
        (draw_function or panel.draw_match_panel)(Layout(log), bpy.context)
        return log

    def summary(log):
        return {"operators": [[e["id"], e["text"], e["props"]] for e in log if e["kind"] == "operator"],
                "props": [[e["data"], e["prop"], e["kind"], e["slider"]]
                          for e in log if e["kind"] in ("prop", "template_icon_view")],
                "labels": [e["text"] for e in log if e["kind"] == "label"],
                "progress": [[e["factor"], e["text"]] for e in log if e["kind"] == "progress"]}

    # a plane with a material slot, the file left unsaved
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj)
    bpy.ops.mesh.primitive_plane_add(size=2)
    plane = bpy.context.view_layer.objects.active
    plane.data.materials.append(bpy.data.materials.new("Existing"))
    settings = bpy.context.scene.blender_match
    settings.photo_path = PHOTO
    items = properties.graph_items(settings, bpy.context)
    out["graph_items"] = [[i[0], i[1], isinstance(i[3], (int, str)), i[4]] for i in items]
    out["families"] = [i[0] for i in properties.family_items(settings, bpy.context)]
    settings.graph = "plaster"
    settings.graph_family = "wood"
    out["wood_items"] = [[i[0], i[4]] for i in properties.graph_items(settings, bpy.context)]
    out["graph_outside_family"] = settings.graph
    settings.graph_family = "ALL"
    settings.graph = "plaster"
    settings.quality = "draft"
    settings.size = "1K"
    settings.device = "cpu"
    out["idle"] = summary(draw())
    mark("idle")

    # a match in an unsaved file, by the operator (the panel's settings for what the call leaves
    # out); the panel is drawn while the operator polls the job: at the first fitting event and
    # at the first one after an iteration (with the time left)
    drawn = {}
    original_poll = match_job._Job.poll

    def poll_and_draw(job):
        done = original_poll(job)
        progress = job.progress or {}
        if not done and progress.get("stage") == "fitting":
            key = "running_iteration" if progress.get("iteration") is not None else "running"
            drawn.setdefault(key, summary(draw()))
        return done

    match_job._Job.poll = poll_and_draw
    try:
        out["match"] = sorted(bpy.ops.blender_match.match_photo(size=64, iterations=3, wait=True))
    except RuntimeError as exc:
        out["match"] = str(exc)
    finally:
        match_job._Job.poll = original_poll
    out.update(drawn)
    material = plane.active_material
    out["material"] = {"name": material.name,
                       "packed": sorted(n.image.packed_file is not None for n in material.node_tree.nodes
                                        if n.type == "TEX_IMAGE"),
                       "result_dir": material["blender_match"]["result_dir"], "tempdir": bpy.app.tempdir,
                       "last": match_job.LAST.get(bpy.context.scene.session_uid)}
    mark("match")
    settings.export_format = "OPEN_EXR"
    settings.export_high_depth = True
    settings.export_preset = "unity"
    out["finished"] = summary(draw())
    # an automatic match's alternatives: a Match button each, for the same photo and quality
    record = material["blender_match"]
    out["photo"] = PHOTO
    out["record_origin"] = {k: record.get(k) for k in ("photo", "photo_image", "quality", "alternatives")}
    record["alternatives"] = ["stucco", "painted_wall"]
    out["alternatives_file"] = summary(draw())
    del record["photo"]
    record["photo_image"] = "Photo Image"
    out["alternatives_image"] = summary(draw())
    del record["photo_image"]
    out["alternatives_no_photo"] = summary(draw())
    del record["alternatives"]
    record["photo"] = PHOTO

    # Cancel, pressed as soon as a job has started
    job = match_job.start_match(bpy.context, photo=PHOTO, graph="plaster", size=64, quality="draft",
                                iterations=300, device="cpu")
    out["starting"] = summary(draw())
    out["cancel_op"] = sorted(bpy.ops.blender_match.cancel())
    out["cancelling"] = summary(draw())
    job.wait(timeout=120)
    out["cancelled"] = summary(draw())
    out["cancelled_state"] = job.state
    mark("cancelled")

    # the preferences, the worker probe, a backend setup that cannot work
    out["preferences"] = summary(draw(lambda layout, context: preferences.draw_preferences(prefs, layout, context)))
    out["probe"] = sorted(bpy.ops.blender_match.probe_worker(wait=True))
    out["probe_message"] = match_job.SERVICES["probe"].message
    mark("probe")
    out["preferences_after_probe"] = summary(
        draw(lambda layout, context: preferences.draw_preferences(prefs, layout, context)))
    # a user library named in the preferences reaches the graph menu and the workers' environment
    prefs.user_library = USER_LIBRARY
    out["user_library"] = {"env": os.environ.get("BLENDER_MATCH_LIBRARY"),
                           "thumbnail": str(addon.thumbnail_file("my_plaster")),
                           "graphs": [n for n, g in addon.library_graphs().items() if g["library"] == "user"]}
    out["user_library_preferences"] = summary(
        draw(lambda layout, context: preferences.draw_preferences(prefs, layout, context)))
    prefs.user_library = ""
    out["user_library_cleared"] = [n for n, g in addon.library_graphs().items() if g["library"] == "user"]
    try:
        out["setup"] = sorted(bpy.ops.blender_match.setup_backend(base_python="/no/such/python", wait=True))
    except RuntimeError as exc:
        out["setup"] = str(exc)

    # the Shader Editor panel shows in shader trees only
    editor = bpy.types.BLENDER_MATCH_PT_shader_editor
    out["shader_poll"] = [editor.poll(SimpleNamespace(space_data=SimpleNamespace(type="NODE_EDITOR", tree_type=t)))
                          for t in ("ShaderNodeTree", "GeometryNodeTree")]
    out["panels"] = [[c.bl_space_type, c.bl_region_type, c.bl_category]
                     for c in (bpy.types.BLENDER_MATCH_PT_view3d, editor)]

    addon_utils.disable("blender_match", default_set=True)
    out["disabled"] = {"enabled": "blender_match" in bpy.context.preferences.addons,
                       "new_types": sorted(set(dir(bpy.types)) - types_before),
                       "scene_prop": hasattr(bpy.types.Scene, "blender_match"),
                       "timers": len(match_job.TIMERS), "jobs": len(match_job.JOBS),
                       "torch": "torch" in sys.modules}
    mark("end")
    print("RESULT " + json.dumps(out))
""")


@pytest.fixture(scope="module")
def session(tmp_path_factory, plaster_photo) -> dict:
    work = tmp_path_factory.mktemp("ui")
    user_library = work / "user library"
    (work / "My Plaster.sbs").write_bytes((GRAPHS / "plaster.sbs").read_bytes())
    started_with = os.environ[USER_LIBRARY_ENV]
    os.environ[USER_LIBRARY_ENV] = str(user_library)
    try:
        add_entry(work / "My Plaster.sbs")
    finally:
        os.environ[USER_LIBRARY_ENV] = started_with
    env = {**os.environ, "BLENDER_USER_RESOURCES": str(work / "blender-user"),
           "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]).rstrip(os.pathsep)}
    return run_blender_script(SESSION, [str(plaster_photo), str(user_library)], work, env, timeout=600)


def _ops(drawn) -> list[str]:
    return [op[0] for op in drawn["operators"]]


def test_library_thumbnails_exist_for_every_graph():
    names = sorted(p.stem for p in GRAPHS.glob("*.json") if (GRAPHS / f"{p.stem}.sbs").is_file())
    assert len(names) == 50
    for name in names:
        png = (GRAPHS / f"{name}.png").read_bytes()
        assert png[:8] == b"\x89PNG\r\n\x1a\n", name
        width, height = struct.unpack(">II", png[16:24])
        assert (width, height) == (128, 128), name


def test_write_thumbnails(tmp_path):
    [path] = write_thumbnails(["plaster"], size=32, out_dir=tmp_path)
    assert path == tmp_path / "plaster.png"
    assert struct.unpack(">II", path.read_bytes()[16:24]) == (32, 32)
    assert write_thumbnails(["plaster"], size=32, out_dir=tmp_path) == []  # kept unless overwrite
    assert write_thumbnails(["plaster"], size=32, out_dir=tmp_path, overwrite=True) == [path]
    with pytest.raises(OptionError, match="not library graphs: nope"):
        write_thumbnails(["nope"], out_dir=tmp_path)


def test_settings_and_graph_menu(session):
    assert session["enabled"]
    items = session["graph_items"]
    assert items[0][:2] == ["AUTO", "Automatic"]
    names = sorted(p.stem for p in GRAPHS.glob("*.json"))
    assert [i[0] for i in items[1:]] == names and all(i[2] for i in items)
    assert [i[3] for i in items] == list(range(len(items)))
    # the family menu: all, then the families that have graphs, in catalog order
    assert session["families"][0] == "ALL" and {"wood", "metal", "stone", "fabric"} <= set(session["families"])
    numbers = {i[0]: i[3] for i in items}
    wood = session["wood_items"]
    assert wood[0] == ["AUTO", 0] and {"raw_wood", "wood_planks"} <= {n for n, _ in wood[1:]}
    assert "plaster" not in {n for n, _ in wood} and all(numbers[n] == k for n, k in wood)
    assert session["graph_outside_family"] == "AUTO"  # plaster is not a wood: back to Automatic
    # loaded as a plain module, not an extension: the backend lives under the user's scripts
    assert session["backend_dir"].endswith("scripts/blender_match_backend")


def test_idle_panel_shows_the_settings_and_match(session):
    idle = session["idle"]
    assert ["blender_match.match_photo", "Match", {}] in idle["operators"]
    assert "blender_match.cancel" not in _ops(idle) and not idle["progress"]
    props = {p[1] for p in idle["props"] if p[0] == "BLENDER_MATCH_PG_settings"}
    assert {"photo_source", "photo_path", "graph", "quality", "size", "device", "calibrate", "match_scale", "pack",
            "tiling"} <= props
    assert ["BLENDER_MATCH_PG_settings", "graph", "template_icon_view", False] in idle["props"]
    # the active material is not a matched one: no result, re-render or export yet
    assert not {"blender_match.rerender", "blender_match.export_maps"} & set(_ops(idle))


def test_panel_during_a_job_shows_progress_and_cancel(session):
    for key in ("running", "running_iteration"):
        running = session[key]
        assert "blender_match.match_photo" not in _ops(running)
        assert ["blender_match.cancel", "Cancel", {}] in running["operators"]
        [[factor, text]] = running["progress"]
        assert 0 < factor < 1 and text.startswith("Fitting graph 1 of 1 (plaster)")
    [[_, text]] = session["running_iteration"]["progress"]
    assert text.startswith("Fitting graph 1 of 1 (plaster), iteration ") and text.endswith(" left")
    assert "/3" in text  # iterations=3 from the operator call
    # the Cancel button on a job that has just started
    assert session["starting"]["progress"] == [[0.0, "Starting the worker"]]
    assert session["cancel_op"] == ["FINISHED"]
    assert session["cancelling"]["progress"][0][1] == "Cancelling"
    assert session["cancelled_state"] == "cancelled"
    cancelled = session["cancelled"]
    assert "blender_match.match_photo" in _ops(cancelled) and not cancelled["progress"]
    assert "Cancelled: nothing was changed" in cancelled["labels"]


def test_panel_after_a_match_shows_the_result_and_its_tools(session):
    assert session["match"] == ["FINISHED"]
    material = session["material"]
    # unsaved file: the maps went to Blender's temporary folder and are packed
    assert material["result_dir"].startswith(material["tempdir"]) and material["packed"] == [True] * 4
    assert material["last"]["graph"] == "plaster"
    finished = session["finished"]
    labels = finished["labels"]
    assert material["name"] in labels and "Graph: plaster" in labels
    assert any(label.startswith("Loss: ") and "Size: 64 px" in label for label in labels)
    assert any(label.startswith("Time: ") for label in labels)
    ops = {op[0]: op for op in finished["operators"]}
    assert ops["blender_match.rerender"][2] == {"size": "4K"}
    assert ops["blender_match.export_maps"][2] == {"preset": "unity", "size": 0, "file_format": "OPEN_EXR",
                                                    "bits": 32}
    assert {"blender_match.apply_parameters", "blender_match.reset_parameters"} <= set(ops)
    sliders = {p[1:] for p in map(tuple, finished["props"]) if p[0] == "BLENDER_MATCH_PG_parameter"}
    assert ("color", "prop", False) in sliders
    assert ("value", "prop", True) in sliders  # [0, 1] parameters: sliders
    assert ("value_wide", "prop", False) in sliders  # plaster's bump_scale is in [0.5, 2]
    assert len([p for p in finished["props"] if p[0] == "BLENDER_MATCH_PG_parameter"]) == 6


def test_an_automatic_matchs_alternatives_are_buttons_that_match_them(session):
    # the match's record says what it came from; a named match has no alternatives to offer
    assert session["record_origin"] == {"photo": session["photo"], "photo_image": None, "quality": "draft",
                                        "alternatives": None}
    assert "Also close:" not in session["finished"]["labels"]
    for key, photo in (("alternatives_file", {"filepath": session["photo"]}),
                       ("alternatives_image", {"image": "Photo Image"})):
        drawn = session[key]
        assert "Also close:" in drawn["labels"]
        matches = [op for op in drawn["operators"] if op[0] == "blender_match.match_photo" and op[1] != "Match"]
        # each new material will offer the other two of the ranking's top 3 in turn
        assert matches == [["blender_match.match_photo", "Stucco",
                            {"graph": "stucco", "alternatives": "plaster,painted_wall", **photo, "quality": "draft"}],
                           ["blender_match.match_photo", "Painted Wall",
                            {"graph": "painted_wall", "alternatives": "plaster,stucco", **photo, "quality": "draft"}]]
    # without the photo there is nothing to match them with
    assert "Also close:" not in session["alternatives_no_photo"]["labels"]


def test_preferences_probe_and_setup(session):
    prefs = session["preferences"]
    assert {"worker_python", "default_device", "pip_arguments"} <= {p[1] for p in prefs["props"]}
    assert {"blender_match.setup_backend", "blender_match.probe_worker"} <= set(_ops(prefs))
    assert any(label.startswith("Worker Python: ") for label in prefs["labels"])
    assert session["probe"] == ["FINISHED"]
    assert "torch " in session["probe_message"] and "devices: cpu" in session["probe_message"]
    assert any("torch " in label for label in session["preferences_after_probe"]["labels"])
    assert session["setup"].startswith("Error: cannot set up the backend: the Python /no/such/python does not exist")


def test_preferences_user_library(session):
    """The folder set in the preferences is the one the catalogue (and every worker, through the
    environment) reads; emptied, the folder Blender started with comes back."""
    chosen = session["user_library"]
    assert chosen["env"].endswith("user library")
    assert chosen["graphs"] == ["my_plaster"]
    assert chosen["thumbnail"] == str(Path(chosen["env"]) / "graphs" / "my_plaster.png")
    assert "user_library" in {p[1] for p in session["user_library_preferences"]["props"]}
    labels = session["user_library_preferences"]["labels"]
    assert any(label.startswith("1 graph(s) of your own in ") for label in labels)
    assert session["user_library_cleared"] == []


def test_panels_and_disable(session):
    assert session["shader_poll"] == [True, False]
    assert session["panels"] == [["VIEW_3D", "UI", "Match"], ["NODE_EDITOR", "UI", "Match"]]
    assert session["disabled"] == {"enabled": False, "new_types": [], "scene_prop": False, "timers": 0, "jobs": 0,
                                   "torch": False}
