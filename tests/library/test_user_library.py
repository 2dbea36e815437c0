"""The user library (``library.user``, ``library.catalog``): real .sbs files added to a folder of
the test's own, listed and loaded beside the shipped graphs, refused with one line, removed."""
from __future__ import annotations

import json

import pytest
import sbs_snippets as W
import torch

from blender_match.library import (
    GRAPHS_DIR,
    LibraryError,
    builtin_names,
    library_entry,
    library_names,
    library_path,
    load_library_graph,
    models_folder,
    sample_params,
    thumbnail_file,
    user_library_dir,
    user_names,
)
from blender_match.library.catalog import USER_LIBRARY_ENV
from blender_match.library.user import add_entry, entry_name, remove_entry
from blender_match.translator import local_dependencies


@pytest.fixture()
def library(tmp_path, monkeypatch):
    folder = tmp_path / "my library"
    monkeypatch.setenv(USER_LIBRARY_ENV, str(folder))
    return folder


@pytest.fixture()
def plaster_copy(tmp_path):
    path = tmp_path / "downloads" / "Plaster Wall-02.sbs"
    path.parent.mkdir()
    path.write_bytes((GRAPHS_DIR / "plaster.sbs").read_bytes())
    return path


def _sub_package(colour="0 1 0 1"):
    color = W.dyn_param("outputcolor", 1, [W.fnode(1, "get_float4", data=("constantValueString", "tint"),
                                                   type_code=2048)])
    nodes = [W.filter_node(10, "uniform", params=[color], outputs=[(11, 1)]), W.output_node(20, 200, 10, 11)]
    return W.package([W.graph("Sub", nodes, outputs=[(200, "out", "baseColor")],
                              paraminputs=[W.paraminput("tint", 6, 2048, "constantValueFloat4", colour)])])


def _main_package(dependency: str):
    nodes = [W.instance_node(10, "pkg:///Sub?dependency=9", outputs=[(11, "out", 1)]), W.output_node(20, 100, 10, 11)]
    return W.package([W.graph("Main", nodes, outputs=[(100, "basecolor", "baseColor")])],
                     dependencies=[(9, dependency), (8, "sbs://noise_perlin_noise.sbs")])


@pytest.mark.parametrize(("file", "name"), [("Plaster Wall-02.sbs", "plaster_wall_02"), ("bricks.sbs", "bricks"),
                                            ("2024 Oak.sbs", "m_2024_oak"), ("Ölfarbe!.sbs", "lfarbe")])
def test_entry_names(file, name):
    assert entry_name(file) == name


def test_user_library_dir_follows_the_environment(library, monkeypatch):
    assert user_library_dir() == library
    monkeypatch.delenv(USER_LIBRARY_ENV)
    monkeypatch.setenv("XDG_DATA_HOME", "/data home")
    assert str(user_library_dir()).endswith("blender_match/library")


def test_an_added_graph_is_listed_loaded_and_sampled_beside_the_shipped_ones(library, plaster_copy):
    meta = add_entry(plaster_copy)
    assert meta["name"] == "plaster_wall_02" and meta["origin"] == str(plaster_copy)
    assert user_names() == ["plaster_wall_02"]
    assert library_names() == builtin_names() + ["plaster_wall_02"]
    entry = library_entry("plaster_wall_02")
    assert entry["library"] == "user" and library_entry("plaster")["library"] == "built-in"
    assert library_path("plaster_wall_02") == library / "graphs" / "plaster_wall_02" / "Plaster Wall-02.sbs"
    assert library_path("plaster_wall_02").read_bytes() == plaster_copy.read_bytes()
    assert thumbnail_file("plaster_wall_02").is_file() and models_folder("plaster_wall_02") == library / "models"
    assert entry["nodes"] == library_entry("plaster")["nodes"]
    # every optimisable parameter is sampled around its authored value
    assert len(entry["sample_ranges"]) > 10
    assert sample_params("plaster_wall_02", 3) != sample_params("plaster_wall_02", 4)
    plaster_copy.unlink()  # the entry holds its own copy
    with torch.no_grad():
        ours = load_library_graph("plaster_wall_02")(size=32, seed=1)["basecolor"]
        shipped = load_library_graph("plaster")(size=32, seed=1)["basecolor"]
    torch.testing.assert_close(ours, shipped)


def test_names_are_checked_and_nothing_is_replaced_without_overwrite(library, plaster_copy):
    with pytest.raises(LibraryError, match="^plaster: a built-in graph has that name"):
        add_entry(plaster_copy, name="plaster")
    with pytest.raises(LibraryError, match="not a valid library name"):
        add_entry(plaster_copy, name="Bad Name")
    add_entry(plaster_copy, name="wall")
    before = (library / "graphs" / "wall.json").read_bytes()
    with pytest.raises(LibraryError, match="already in the user library .*--overwrite"):
        add_entry(plaster_copy, name="wall")
    assert (library / "graphs" / "wall.json").read_bytes() == before
    add_entry(plaster_copy, name="wall", overwrite=True)
    assert user_names() == ["wall"]


def test_a_user_graph_named_like_a_shipped_one_is_not_listed(library, plaster_copy):
    add_entry(plaster_copy, name="wall")
    (library / "graphs" / "wall.json").rename(library / "graphs" / "bricks.json")
    (library / "graphs" / "wall").rename(library / "graphs" / "bricks")
    assert user_names() == [] and library_entry("bricks")["library"] == "built-in"


@pytest.mark.parametrize(("text", "problem"), [
    ("<package><content>", "malformed XML"),
    (W.package([]), "no graph with outputs"),
])
def test_a_file_that_cannot_be_rendered_is_refused_in_one_line(library, tmp_path, text, problem):
    bad = tmp_path / "bad.sbs"
    bad.write_text(text)
    with pytest.raises(LibraryError) as caught:
        add_entry(bad)
    message = str(caught.value)
    assert str(bad) in message and problem in message and "\n" not in message
    assert not (library / "graphs").exists() or list((library / "graphs").iterdir()) == []


def test_refusals_name_the_file(library, tmp_path):
    with pytest.raises(LibraryError, match="no such file"):
        add_entry(tmp_path / "missing.sbs")
    (tmp_path / "photo.png").write_bytes(b"png")
    with pytest.raises(LibraryError, match="photo.png: not a Substance .sbs file"):
        add_entry(tmp_path / "photo.png")


def test_local_dependencies_are_copied_with_the_file(library, tmp_path):
    (tmp_path / "parts").mkdir()
    (tmp_path / "parts" / "sub.sbs").write_text(_sub_package())
    main = tmp_path / "main.sbs"
    main.write_text(_main_package("parts/sub.sbs"))
    assert local_dependencies(main) == ["parts/sub.sbs"]
    add_entry(main)
    (tmp_path / "parts" / "sub.sbs").unlink()
    assert (library / "graphs" / "main" / "parts" / "sub.sbs").is_file()
    with torch.no_grad():
        colour = load_library_graph("main")(size=8)["basecolor"][0, :, 0, 0]
    torch.testing.assert_close(colour, torch.tensor([0.0, 1.0, 0.0, 1.0]))


def test_a_dependency_outside_the_folder_is_refused(library, tmp_path):
    (tmp_path / "sub.sbs").write_text(_sub_package())
    (tmp_path / "materials").mkdir()
    main = tmp_path / "materials" / "main.sbs"
    main.write_text(_main_package("../sub.sbs"))
    with pytest.raises(LibraryError, match=r"main.sbs: depends on \.\./sub\.sbs, outside the file's folder"):
        add_entry(main)
    assert user_names() == []


def test_remove_takes_every_file_of_an_entry_and_nothing_else(library, plaster_copy):
    add_entry(plaster_copy, name="wall")
    add_entry(plaster_copy, name="wall_two")
    (library / "models").mkdir()
    (library / "models" / "wall.bank.pt").write_bytes(b"bank")
    (library / "models" / "wall_two.bank.pt").write_bytes(b"bank")
    removed = remove_entry("wall")
    assert {p.name for p in removed} == {"wall.json", "wall.png", "wall.bank.pt", "wall"}
    assert user_names() == ["wall_two"] and (library / "models" / "wall_two.bank.pt").is_file()
    assert json.loads((library / "graphs" / "wall_two.json").read_text())["name"] == "wall_two"
    with pytest.raises(LibraryError, match="wall: not in the user library"):
        remove_entry("wall")
    with pytest.raises(LibraryError, match="bricks: a built-in graph"):
        remove_entry("bricks")
